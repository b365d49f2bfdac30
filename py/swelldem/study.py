# SPDX-License-Identifier: GPL-2.0-or-later
"""Studies: many swelling tests (scripts/swelling_test.py runs) on Dask distributed, from one
machine to a cluster, with the same call.

A study is a list of Run(name, settings): settings are SwellingTest fields, the run writes into
<out>/<name>/. run_study() hands each run to a Dask worker, which starts it as its own process
(scripts/yade-swelldem -j 1, one thread) and waits for it:

- without a scheduler address it starts a local cluster on this machine (`jobs` worker
  processes, one thread each); with one (`tcp://host:8786`) it submits to a running Dask
  scheduler, whose workers are started with `scripts/study-worker ADDRESS` on any machine where
  the project is set up at the same path and the study's folder is reachable at the same path
  (docs/guide.md, "Studies on a cluster");
- it resumes: a run whose results.json finished with the run's settings is kept, a folder that
  holds a finished run of other settings stops the study before any work, any other (failed,
  interrupted, killed, absent) runs again;
- a run whose worker dies (the machine lost, the worker killed) is run again on another worker:
  Dask's scheduler reschedules a task whose worker left (its allowed-failures, 3), and the run's
  process dies with its worker (PR_SET_PDEATHSIG) so that two attempts never write into one
  folder for long;
- <out>/runs.json and runs.md record per run its state, the worker and host that ran it, its
  wall time and every attempt; <out>/progress.md and one line per event on stdout show runs
  done, running and left with an estimate of the time left;
- SIGINT or SIGTERM stops the running runs (each writes 'interrupted' into its results.json) and
  the study; the next call goes on from there.

Plain Python; Dask is imported only when a study runs (Debian's python3-distributed).
"""
import ast
import ctypes
import json
import math
import os
import re
import signal
import socket
import subprocess
import sys
import time
from dataclasses import MISSING, asdict, dataclass, fields

from . import options
from .scenario import SwellingTest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LAUNCHER = os.path.join(REPO, "scripts", "yade-swelldem")
SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")
#: Dask event topic on which the workers report a run's start (the client's progress).
TOPIC = "swelldem-study"
#: Settings a study cannot set per run: the study places each run's folder itself.
NOT_PER_RUN = ("out",)


@dataclass
class Run:
    """One run of a study: its folder name under the study's folder and its SwellingTest fields
    (those left out keep the field's default)."""
    name: str
    settings: dict

    def test(self, out):
        """The SwellingTest of this run in the study folder `out` (not validated)."""
        kw = dict(self.settings)
        if isinstance(kw.get("size_mm"), (list, tuple)):
            kw["size_mm"] = tuple(float(v) if options.is_number(v) else v for v in kw["size_mm"])
        return SwellingTest(out=os.path.join(out, self.name), **kw)


def field_names():
    return [f.name for f in fields(SwellingTest)]


def _field_defaults():
    return {f.name: (f.default_factory() if f.default is MISSING else f.default) for f in fields(SwellingTest)}


def command_options(settings):
    """swelling_test.py's options for the SwellingTest fields `settings` (every field but out):
    the flags of the fields' metadata (scenario.add_arguments makes the same parser); floats in
    repr so that the run gets the exact value; None (the solver's own default) left out."""
    defaults = _field_defaults()
    flags = {f.name: f.metadata.get("flag") or f"--{f.name.replace('_', '-')}" for f in fields(SwellingTest)}
    out = []
    for name, value in settings.items():
        if name not in flags or name in NOT_PER_RUN:
            options.bad("study setting", name, ", ".join(n for n in flags if n not in NOT_PER_RUN))
        if value is None:
            continue
        if isinstance(defaults[name], bool):
            if value != defaults[name]:
                out.append(f"--no-{name.replace('_', '-')}" if defaults[name] else flags[name])
        elif isinstance(value, (tuple, list)):
            out += [flags[name], *[repr(float(v)) for v in value]]
        elif name == "kind_params":
            out += [w for kind, attrs in value.items() for attr, v in attrs.items() for w in (flags[name], f"{kind}.{attr}={v!r}")]
        elif name == "solver_params":
            out += [w for k, v in value.items() for w in (flags[name], f"{k}={v!r}")]
        elif name == "shrinkage":
            out += [w for k, v in value.items() for w in (flags[name], f"{k}={float(v)!r}")]
        elif name == "humidity_faces":
            out += [w for face, v in value.items() for w in (flags[name], face, repr(float(v)) if options.is_number(v) else str(v))]
        else:
            out += [flags[name], repr(value) if isinstance(value, float) else str(value)]
    return out


def command(run, out):
    """The command that makes `run` in the study folder `out`."""
    return [LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *command_options(run.settings), "--out", os.path.join(out, run.name)]


def _json(v):
    return json.loads(json.dumps(v, default=float))


def expected_config(run, out):
    """results.json's config of `run` as a finished run records it (every SwellingTest field, JSON
    values), without out."""
    cfg = _json(asdict(run.test(out)))
    for k in NOT_PER_RUN:
        cfg.pop(k, None)
    return cfg


def differing(cfg, want):
    """{field: (recorded, wanted)} of a run's recorded config against the study's; a field the
    record lacks (a run made by an older swelldem) counts as what that swelldem did: its default,
    or scenario.VALUE_BEFORE_FIELD."""
    from .scenario import VALUE_BEFORE_FIELD
    defaults = {**_json(_field_defaults()), **VALUE_BEFORE_FIELD}
    return {k: (cfg.get(k, defaults.get(k)), v) for k, v in want.items() if cfg.get(k, defaults.get(k)) != v}


def folder_state(folder, want):
    """('finished', {}) for a run in `folder` that finished with the config `want`, ('other', diff)
    for one that finished with other settings, ('todo', {}) otherwise (absent, failed,
    interrupted, killed, unreadable)."""
    try:
        with open(os.path.join(folder, "results.json")) as f:
            res = json.load(f)
    except (OSError, ValueError):
        return "todo", {}
    if not isinstance(res, dict) or res.get("status") != "finished":
        return "todo", {}
    diff = differing(res.get("config") or {}, want)
    return ("other", diff) if diff else ("finished", {})


# -- a table of runs -----------------------------------------------------------------------------

def run_name(description, line):
    # a name made of the columns (e.g. "scenario='isr',seed=3") holds quotes and commas
    name = re.sub(r"[^A-Za-z0-9._=+-]+", "_", str(description)).strip("_")
    return name or f"line{line}"


def _word(v):
    """A value as a word of a run's name: 'isr' -> isr, (40, 40) -> 40x40."""
    if isinstance(v, (tuple, list)):
        return "x".join(_word(x) for x in v)
    return f"{v:g}" if isinstance(v, float) else str(v)


def read_table(path):
    """The runs of a table in yade-batch's form (scripts/swelling_sweep.table): a header line of
    column names, then one run a line; columns separated by blanks, each value a Python literal
    without blanks ('isr' quoted, True, (40,40), {'MORTAR':{'tensileStrength':5e6}}), '=' the
    value of the line above; '#' starts a comment. Each column sets the SwellingTest field of its
    name; a 'description' column names the run's folder, else the columns do. OptionError naming
    the file and line for anything else, before any work."""
    names = set(field_names()) - set(NOT_PER_RUN)
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        options.bad("table", path, f"a readable table file ({e.strerror})")
    header, runs, previous = None, [], {}
    for number, text in enumerate(lines, start=1):
        text = text.split("#", 1)[0].strip()
        if not text:
            continue
        words = text.split()
        if header is None:
            header = words
            for col in header:
                if col != "description" and col not in names:
                    options.bad("table column", f"{path}:{number}: {col}", ", ".join(["description"] + sorted(names)))
            if len(set(header)) != len(header):
                options.bad("table header", f"{path}:{number}", "distinct column names")
            continue
        if len(words) != len(header):
            options.bad("table line", f"{path}:{number}", f"{len(header)} values, one a column ({' '.join(header)})")
        row = {}
        for col, word in zip(header, words):
            if word == "=":
                if col not in previous:
                    options.bad("table value", f"{path}:{number}: {col} =", "a value ('=' repeats the line above; this is the first)")
                row[col] = previous[col]
            elif col == "description":
                row[col] = word
            else:
                try:
                    row[col] = ast.literal_eval(word)
                except (ValueError, SyntaxError):
                    options.bad("table value", f"{path}:{number}: {col} {word}", "a Python literal without blanks, strings quoted: 'isr'")
        previous = row
        settings = {k: v for k, v in row.items() if k != "description"}
        desc = row.get("description") or ",".join(f"{k}={_word(v)}" for k, v in settings.items())
        runs.append(Run(run_name(desc, number), settings))
    if not runs:
        options.bad("table", path, "a header line and at least one run")
    return runs


def with_seeds(runs, seeds):
    """Each run once a seed, named <name>-s<seed>; a run that sets its own seed is refused."""
    seeds = list(seeds)
    for s in seeds:
        options.integer("seeds", s, lo=0)
    if len(set(seeds)) != len(seeds):
        options.bad("seeds", tuple(seeds), "distinct seeds")
    for r in runs:
        if "seed" in r.settings:
            options.bad("seeds", tuple(seeds), f"left out: run {r.name} sets its own seed ({r.settings['seed']})")
    return [Run(f"{r.name}-s{s}", {**r.settings, "seed": s}) for r in runs for s in seeds]


def check(runs, out):
    """Every run's settings (SwellingTest.validate, the mesostructure generator's limits
    included), distinct names, and the finished runs already in `out`: all before any work.
    Returns {name: (state, expected config)}."""
    options.output_folder("out", out)
    names = [r.name for r in runs]
    if len(set(names)) != len(names):
        twice = sorted({n for n in names if names.count(n) > 1})
        options.bad("run names", ", ".join(twice), "one folder a run: distinct descriptions")
    states = {}
    for r in runs:
        command_options(r.settings)  # a setting that is not a field
        try:
            test = r.test(out)
        except TypeError as e:
            options.bad("run", r.name, f"SwellingTest fields ({e})")
        try:
            test.validate()
        except ValueError as e:  # the field checks' and the mesostructure generator's
            raise options.OptionError(f"run {r.name}: {e}") from None
        want = expected_config(r, out)
        state, diff = folder_state(os.path.join(out, r.name), want)
        if state == "other":
            text = ", ".join(f"{k} {a!r} (asked {b!r})" for k, (a, b) in sorted(diff.items()))
            options.bad("out", out, f"a new folder or one of a study with the same settings: {r.name} there finished with {text}")
        states[r.name] = state
    return states


# -- on a worker ---------------------------------------------------------------------------------

_RUNNING = {}  # in a worker process: the study token -> {run name: Popen}


def _die_with_parent():
    # the run is the worker's child: if the worker dies (killed, its machine lost), the run gets
    # SIGTERM, writes 'interrupted' and ends, and the run's retry on another worker is alone
    libc = ctypes.CDLL("libc.so.6", use_errno=True)
    libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def execute(token, name, cmd, folder):
    """Runs one swelling test on this worker: its process writes into `folder`, its output into
    <folder>.log. Returns what the study records: status (results.json's), exit code, worker,
    host, start and end time. Runs in a worker's thread; Dask reschedules it when the worker dies."""
    started = time.time()
    try:
        from distributed import get_worker
        worker = get_worker()
        address = worker.address
        worker.log_event(TOPIC, {"token": token, "run": name, "state": "started", "worker": address, "time": started})
    except (ImportError, ValueError):  # outside Dask (a test calling it directly)
        address = "local"
    os.makedirs(folder, exist_ok=True)
    log_path = folder + ".log"
    try:
        os.remove(log_path)  # a new file: the process of an attempt whose worker died keeps its own
    except FileNotFoundError:
        pass
    env = dict(os.environ, OMP_NUM_THREADS="1")
    with open(log_path, "w") as log:
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=env, preexec_fn=_die_with_parent)
        _RUNNING.setdefault(token, {})[name] = proc
        try:
            rc = proc.wait()
        finally:
            _RUNNING.get(token, {}).pop(name, None)
    try:
        with open(os.path.join(folder, "results.json")) as f:
            status = str(json.load(f).get("status", "?"))
    except (OSError, ValueError):
        status = f"no results.json (exit {rc})"
    return {"run": name, "status": status, "exit": rc, "worker": address, "host": socket.gethostname(), "pid": proc.pid,
            "started": started, "ended": time.time()}


def stop_runs(token):
    """On a worker: SIGTERM to the study's running runs (each writes 'interrupted' and ends)."""
    procs = list(_RUNNING.get(token, {}).values())
    for p in procs:
        if p.poll() is None:
            p.send_signal(signal.SIGTERM)
    return len(procs)


# -- the client ----------------------------------------------------------------------------------

def _fmt_s(s):
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.1f} min" if s < 7200 else f"{s / 3600:.1f} h"


class Progress:
    """Progress lines on stdout and <out>/progress.md (rewritten at each event): runs done, running
    and left, and the time left estimated from the runs that ended in this call (their mean wall
    time over the workers; none before the first has ended)."""

    def __init__(self, out, names, prog, quiet=False):
        self.path, self.t0, self.prog, self.quiet = os.path.join(out, "progress.md"), time.time(), prog, quiet
        self.state = {n: "waiting" for n in names}
        self.started, self.walls, self.workers = {}, [], 1

    def counts(self):
        done = sum(s.startswith(("finished", "kept", "failed", "interrupted", "no results")) for s in self.state.values())
        running = sum(s.startswith("running") for s in self.state.values())
        return done, running, len(self.state) - done - running

    def left_s(self):
        if not self.walls:
            return None
        mean = sum(self.walls) / len(self.walls)
        now = time.time()
        _, running, waiting = self.counts()
        busy = sum(max(mean - (now - t), 0.0) for n, t in self.started.items() if self.state[n].startswith("running"))
        return (busy + waiting * mean) / max(self.workers, 1)

    def set(self, name, state):
        self.state[name] = state
        if state.startswith("running"):
            self.started[name] = time.time()
        done, running, waiting = self.counts()
        left = self.left_s()
        eta = f", about {_fmt_s(left)} left" if left is not None and (running or waiting) else ""
        if not self.quiet:
            print(f"{self.prog}: [{time.time() - self.t0:7.0f} s] {name}: {state} ({done} done, {running} running, {waiting} waiting of "
                  f"{len(self.state)}{eta})", flush=True)
        lines = [f"# {self.prog}: progress", "", f"{done} done, {running} running, {waiting} waiting of {len(self.state)}{eta} "
                 f"(updated {time.strftime('%Y-%m-%d %H:%M:%S UTC', time.gmtime())})", "",
                 "| run | state |", "|---|---|"] + [f"| {n} | {s} |" for n, s in self.state.items()]
        with open(self.path + ".tmp", "w") as f:
            f.write("\n".join(lines) + "\n")
        os.replace(self.path + ".tmp", self.path)


def _record(out, runs, record):
    """<out>/runs.json and runs.md: per run its state, worker, host, wall time and attempts."""
    with open(os.path.join(out, "runs.json.tmp"), "w") as f:
        json.dump({"runs": record}, f, indent=1)
    os.replace(os.path.join(out, "runs.json.tmp"), os.path.join(out, "runs.json"))
    lines = ["| run | state | worker | host | wall [s] | attempts |", "|---|---|---|---|---|---|"]
    names = [r.name for r in runs]
    for name in names + sorted(set(record) - set(names)):  # an earlier batch's runs too
        rec = record.get(name, {})
        wall = rec.get("wall_s")
        lines.append(f"| {name} | {rec.get('state', 'waiting')} | {rec.get('worker', '')} | {rec.get('host', '')} | "
                     f"{'' if wall is None else f'{wall:.1f}'} | {len(rec.get('attempts', []))} |")
    with open(os.path.join(out, "runs.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def _client(jobs, scheduler):
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        sys.exit("study: Dask distributed is missing (Debian python3-distributed); run scripts/setup.sh")
    if scheduler:
        return Client(scheduler, timeout=30), None
    cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None, host="127.0.0.1")
    return Client(cluster), cluster


class Runner:
    """Dask workers for one or more batches of runs: a local cluster of `jobs` processes (one
    thread each) or a running scheduler's workers (`scheduler` address), connected at the first
    batch that has work and kept until close() (a context manager). run() is one batch."""

    def __init__(self, jobs=1, scheduler=None, prog="study"):
        self.jobs, self.scheduler, self.prog = jobs, scheduler, prog
        self.client = self.cluster = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()
        self.client = self.cluster = None
        if self._main_file is not None:
            sys.modules["__main__"].__file__ = self._main_file
            self._main_file = None

    _main_file = None

    def connect(self):
        if self.client is None:
            if not self.scheduler:
                # A local worker is a process started by multiprocessing's spawn, which runs the
                # calling script again (as __mp_main__) unless its code sits under a main guard;
                # the workers need nothing of it (execute() is this module's), so while they may be
                # started, restarted included, the script is not named to them.
                main = sys.modules["__main__"]
                if getattr(main, "__spec__", None) is None and getattr(main, "__file__", None):
                    self._main_file = main.__file__
                    del main.__file__
            self.client, self.cluster = _client(self.jobs, self.scheduler)
        return self.client

    def run(self, runs, out, quiet=False):
        """Runs the runs into the folder `out` (check() first); True when every run was done
        (kept or made, whatever its status), False when stopped by a signal."""
        return _run_batch(self, runs, out, quiet)


def end(prog, completed, all_finished):
    """Ends a study script: a stopped study (completed False) says how to go on and exits with status
    1; otherwise status 0 when every run finished, 1 when one did not."""
    if not completed:
        sys.exit(f"{prog}: stopped; call it again with the same options to go on")
    sys.exit(0 if all_finished else 1)


def run_study(runs, out, jobs=1, scheduler=None, prog="study"):
    """Runs the runs of a study into the folder `out` (check() first, then this) on a Runner of its
    own; returns True when every run was done (kept or made, whatever its status), False when
    stopped by a signal. jobs: local workers (one process and one thread each) when no scheduler
    address is given."""
    with Runner(jobs, scheduler, prog) as runner:
        return runner.run(runs, out)


def _run_batch(runner, runs, out, quiet):
    prog, scheduler = runner.prog, runner.scheduler
    os.makedirs(out, exist_ok=True)
    progress = Progress(out, [r.name for r in runs], prog, quiet)
    try:
        with open(os.path.join(out, "runs.json")) as f:
            record = json.load(f).get("runs", {})
    except (OSError, ValueError):
        record = {}
    todo = []
    for r in runs:
        if folder_state(os.path.join(out, r.name), expected_config(r, out))[0] == "finished":
            progress.set(r.name, "kept (finished in an earlier call)")
            record.setdefault(r.name, {})["state"] = "finished"
        else:
            todo.append(r)
    _record(out, runs, record)
    if not todo:
        return True
    token = f"{socket.gethostname()}-{os.getpid()}-{time.time():.0f}"
    stop = []
    handlers = {sig: signal.signal(sig, lambda s, f: stop.append(s)) for sig in (signal.SIGTERM, signal.SIGINT)}
    client = runner.connect()
    try:
        from distributed import as_completed
        progress.workers = max(len(client.scheduler_info().get("workers", {})), 1)
        if not quiet:
            print(f"{prog}: {len(todo)} runs on {progress.workers} Dask workers ({'scheduler ' + scheduler if scheduler else 'a local cluster'}"
                  f"{'; dashboard ' + client.dashboard_link if scheduler else ''})", flush=True)
        futures = {}
        for r in todo:
            fut = client.submit(execute, token, r.name, command(r, out), os.path.join(out, r.name), key=f"{token}-{r.name}", pure=False)
            futures[fut] = r
        pending = as_completed(list(futures))
        seen = 0
        while not pending.is_empty() and not stop:
            progress.workers = max(len(client.scheduler_info().get("workers", {})), 1)
            # the starts read first, the ends then: a run's end reaches the client after the start
            # of the next run on its worker, and is printed before it
            events = client.get_events(TOPIC)[seen:]
            for fut in _ready(pending, wait=not events):
                r = futures[fut]
                rec = record.setdefault(r.name, {})
                try:
                    got = fut.result()
                except Exception as e:  # noqa: BLE001 - a run Dask gave up on (workers died 3 times): recorded, the others go on
                    rec.update(state=f"lost: {type(e).__name__}: {e}")
                    progress.set(r.name, rec["state"])
                    _record(out, runs, record)
                    continue
                wall = got["ended"] - got["started"]
                rec.update(state=got["status"], worker=got["worker"], host=got["host"], wall_s=wall, exit=got["exit"])
                attempt(rec, got["worker"], got["started"]).update(ended=got["ended"], exit=got["exit"])
                progress.walls.append(wall)
                progress.set(r.name, f"{got['status'][:100]} (exit {got['exit']}, {wall:.0f} s on {got['worker']})")
                _record(out, runs, record)
            for ev_time, ev in events:
                seen += 1
                if isinstance(ev, dict) and ev.get("token") == token and ev.get("run") in progress.state:
                    rec = record.setdefault(ev["run"], {})
                    if "ended" in attempt(rec, ev["worker"], ev["time"]):
                        continue  # the run ended before its start was read (a run shorter than a poll)
                    rec.update(state="running", worker=ev["worker"])
                    progress.set(ev["run"], f"running on {ev['worker']}")
                    _record(out, runs, record)
        if stop:
            for fut in futures:
                fut.cancel() if fut.status == "pending" else None
            client.run(stop_runs, token)  # every worker: SIGTERM to this study's runs
            deadline = time.time() + 90
            for fut, r in futures.items():
                try:
                    got = fut.result(timeout=max(deadline - time.time(), 1))
                    progress.set(r.name, f"{got['status'][:100]} (stopped)")
                    record.setdefault(r.name, {})["state"] = got["status"]
                except Exception:  # noqa: BLE001 - cancelled before it started, or not back in time
                    pass
            _record(out, runs, record)
    finally:
        for sig, h in handlers.items():
            signal.signal(sig, h)
    return not stop


def attempt(rec, worker, started):
    """The attempt of a run's record `rec` that `worker` started at `started` (execute()'s clock),
    added when new: a run's start event and its end may be read in either order."""
    attempts = rec.setdefault("attempts", [])
    for a in attempts:
        if a["worker"] == worker and a["started"] == started:
            return a
    attempts.append({"worker": worker, "started": started})
    return attempts[-1]


def _ready(pending, wait=True):
    """The futures of `pending` (distributed.as_completed) that have ended; when none has and
    `wait`, sleeps 1 s (the poll of the progress)."""
    try:
        batch = pending.next_batch(block=False)
    except StopIteration:
        return []
    if not batch and wait:
        time.sleep(1.0)
    return batch


def results_state(out, runs):
    """{name: results.json's status} of the runs in `out` ('absent' for none)."""
    states = {}
    for r in runs:
        try:
            with open(os.path.join(out, r.name, "results.json")) as f:
                states[r.name] = str(json.load(f).get("status", "?"))
        except (OSError, ValueError):
            states[r.name] = "absent"
    return states


#: summary_rows' measures in their order: (key, heading).
MEASURES = ([(f"strain_{a}_1e-6", f"strain {a} [1e-6]") for a in ("x", "y", "z", "area", "volume")]
            + [(f"broken_{k}_pct", f"broken {k} [%]") for k in ("MORTAR", "ITZ", "AGG")]
            + [(f"fn_{q}_{k}_kN", f"F {int(q[1:])} % {k} [kN]") for q in ("p05", "p95") for k in ("MORTAR", "ITZ", "AGG")])


def summary_rows(out, runs):
    """One row per run group (the runs of one table line over its seeds: the name without -s<seed>):
    the final strains and broken shares per kind, mean, min and max over the group's finished runs."""
    groups = {}
    for r in runs:
        base = re.sub(r"-s\d+$", "", r.name)
        groups.setdefault(base, []).append(r)
    rows = []
    for base, members in groups.items():
        vals = {}
        n = 0
        for r in members:
            try:
                with open(os.path.join(out, r.name, "results.json")) as f:
                    res = json.load(f)
            except (OSError, ValueError):
                continue
            if res.get("status") != "finished":
                continue
            n += 1
            for axis in ("x", "y", "z", "volume", "area"):
                s = res.get(f"swelling_strain_{axis}")
                if s:
                    vals.setdefault(f"strain_{axis}_1e-6", []).append(s[-1] * 1e6)
            for kind, series in (res.get("per_kind") or {}).items():
                total = (res.get("n_contacts_by_kind") or {}).get(kind) or 0
                if total and series.get("broken"):
                    vals.setdefault(f"broken_{kind}_pct", []).append(100.0 * series["broken"][-1] / total)
                for q in ("p05", "p95"):
                    if series.get(f"fn_{q}_kN") and math.isfinite(series[f"fn_{q}_kN"][-1]):
                        vals.setdefault(f"fn_{q}_{kind}_kN", []).append(series[f"fn_{q}_kN"][-1])
        row = {"run": base, "seeds": len(members), "finished": n}
        for k, v in vals.items():
            row[f"{k}_mean"], row[f"{k}_min"], row[f"{k}_max"] = sum(v) / len(v), min(v), max(v)
        rows.append(row)
    return rows
