# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's study in one command: its 12 swelling tests (ISR, ASR-fine, ASR-coarse x elastic,
aging viscoelastic x without, with damage) on one specimen size, then its Tables 3.4, 3.6 and
3.7 next to the paper's values and its figures, all in one folder with an index.md.

  /usr/bin/python3 scripts/paper_study.py --size-mm W H --jobs N --out DIR [--seed S] [--steps-per-decade K]
      [--solver adr|implicit]

Each run is scripts/swelling_test.py in its own process (scripts/yade-swelldem -j 1), N at a time,
into DIR/<scenario>-<el|ve>-<nodmg|dmg>/ with its log DIR/<run>.log. Resumable: a run whose
results.json says 'finished' with the same size, seed, steps per decade and solver is kept, any other
(failed, interrupted, killed, absent) runs again; a finished run of other settings in DIR stops the
study before any work (choose another DIR). Ctrl-C or SIGTERM stops the running jobs (their
results.json says 'interrupted'); the next call goes on from there. Progress: one line per run
started and ended, and DIR/progress.md.

DIR then holds index.md (the runs, the three tables, the figures and the paper's figure each one
matches), tables.md, study.csv and per scenario <scenario>_strain.png, <scenario>_unbalanced_nodmg.png,
<scenario>_unbalanced_dmg.png, <scenario>_forces_nodmg.png, <scenario>_forces_dmg.png
(docs/paper-study.md). Exit status 0 when every run finished, 1 when one did not (the tables and
figures show what there is), 2 for bad options (before any work). The solver is the paper's ADR
unless --solver implicit."""
import argparse
import csv
import json
import os
import signal
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper, report, scenario  # noqa: E402
from swelldem.scenario import SwellingTest  # noqa: E402

LAUNCHER = os.path.join(REPO, "scripts", "yade-swelldem")
SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")
#: The plugin's range of LogTimeSolver.stepsPerDecade, checked here so that it stops the study before any run.
STEPS_PER_DECADE_MAX = 10000


def run_names():
    """The 12 runs, the slowest first (damage, then ASR-fine's long kinetics) so that N processes
    end close together."""
    order = {"asr-fine": 0, "isr": 1, "asr-coarse": 2}
    names = [f"{sc}-{b}-{d}" for d in ("dmg", "nodmg") for sc in sorted(paper.SCENARIOS, key=order.get) for b in paper.BEHAVIOUR_KEYS]
    return names


def split(name):
    sc, b, d = name.rsplit("-", 2)
    return sc, b, d


def settings_of(a):
    return {"size_mm": [float(v) for v in a.size_mm], "seed": a.seed, "steps_per_decade": float(a.steps_per_decade), "solver": a.solver}


def check(a):
    """Every option, in the one message form (swelldem.options), before any work; the settings of
    finished runs already in DIR must be this study's."""
    options.output_folder("out", a.out)
    options.integer("jobs", a.jobs, lo=1)
    options.number("steps_per_decade", a.steps_per_decade, lo=0, hi=STEPS_PER_DECADE_MAX, hi_incl=True,
                   allowed=f"0 < steps_per_decade <= {STEPS_PER_DECADE_MAX} [1/decade]")
    # the swelling test's own checks (size, seed, the mesostructure generator's limits)
    SwellingTest(size_mm=tuple(a.size_mm), seed=a.seed, steps_per_decade=a.steps_per_decade, solver=a.solver, out=a.out).validate()
    want = settings_of(a)
    for name in run_names():
        got = finished_settings(os.path.join(a.out, name))
        if got is not None and got != want:
            options.bad("out", a.out, f"a new folder or one of a study with the same settings: {name} there finished with "
                                      f"size_mm {got['size_mm']}, seed {got['seed']}, steps_per_decade {got['steps_per_decade']:g}, "
                                      f"solver {got['solver']}")


def finished_settings(folder):
    """The settings of a finished run in `folder`, or None when it has none that finished."""
    try:
        with open(os.path.join(folder, "results.json")) as f:
            res = json.load(f)
    except (OSError, ValueError):
        return None
    if not isinstance(res, dict) or res.get("status") != "finished":
        return None
    cfg = res.get("config") or {}
    return {"size_mm": [float(v) for v in cfg.get("size_mm", ())], "seed": cfg.get("seed"),
            "steps_per_decade": float(cfg.get("steps_per_decade", float("nan"))), "solver": cfg.get("solver")}


def command(name, a):
    sc, b, d = split(name)
    cmd = [LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, "--scenario", sc, "--behaviour", paper.BEHAVIOUR_KEYS[b],
           "--size-mm", f"{a.size_mm[0]:g}", f"{a.size_mm[1]:g}", "--seed", str(a.seed),
           "--steps-per-decade", f"{a.steps_per_decade:g}", "--solver", a.solver, "--out", os.path.join(a.out, name)]
    return cmd + (["--no-damage"] if d == "nodmg" else [])


class Progress:
    """Progress lines on stdout and DIR/progress.md (rewritten at each event)."""

    def __init__(self, out, names):
        self.path, self.t0 = os.path.join(out, "progress.md"), time.time()
        self.state = {n: "waiting" for n in names}

    def set(self, name, state):
        self.state[name] = state
        done = sum(s.startswith(("finished", "kept")) for s in self.state.values())
        print(f"paper_study: [{time.time() - self.t0:7.0f} s] {name}: {state} ({done}/{len(self.state)} done)", flush=True)
        lines = ["# Paper study: progress", "", "| run | state |", "|---|---|"] + [f"| {n} | {s} |" for n, s in self.state.items()]
        with open(self.path + ".tmp", "w") as f:
            f.write("\n".join(lines) + "\n")
        os.replace(self.path + ".tmp", self.path)


def run_all(a, progress):
    """Runs the runs that have not finished, a.jobs at a time; returns False when stopped by a signal."""
    want = settings_of(a)
    todo = []
    for name in run_names():
        if finished_settings(os.path.join(a.out, name)) == want:
            progress.set(name, "kept (finished in an earlier call)")
        else:
            todo.append(name)
    stop = []
    handlers = {sig: signal.signal(sig, lambda s, f: stop.append(s)) for sig in (signal.SIGTERM, signal.SIGINT)}
    env = dict(os.environ, OMP_NUM_THREADS="1")
    running = {}
    try:
        while (todo or running) and not stop:
            while todo and len(running) < a.jobs:
                name = todo.pop(0)
                log = open(os.path.join(a.out, f"{name}.log"), "w")
                running[name] = (subprocess.Popen(command(name, a), stdout=log, stderr=subprocess.STDOUT, env=env,
                                                  start_new_session=True), log, time.time())
                progress.set(name, "running")
            time.sleep(0.5)
            for name, (proc, log, t0) in list(running.items()):
                if proc.poll() is None:
                    continue
                log.close()
                del running[name]
                progress.set(name, f"{status_of(os.path.join(a.out, name))} (exit {proc.returncode}, {time.time() - t0:.0f} s)")
    finally:
        for name, (proc, log, t0) in running.items():  # stopped: each job writes 'interrupted' into its results.json
            proc.send_signal(signal.SIGTERM)
        for name, (proc, log, t0) in running.items():
            try:
                proc.wait(timeout=60)
            except subprocess.TimeoutExpired:
                proc.kill()
            log.close()
            progress.set(name, f"{status_of(os.path.join(a.out, name))} (stopped)")
        for sig, h in handlers.items():
            signal.signal(sig, h)
    return not stop


def status_of(folder):
    try:
        with open(os.path.join(folder, "results.json")) as f:
            return str(json.load(f).get("status", "?"))
    except (OSError, ValueError):
        return "no results.json"


FIGURES = {  # file suffix -> (what it shows, the paper's figures of the same form per scenario)
    "strain": ("swelling strain in x against log time, the four runs and the free swelling of the swelling phase",
               {"isr": "Figures 3.3 and 3.9 (right)", "asr-fine": "Figures 3.4 and 3.10 (right)", "asr-coarse": "Figures 3.5 and 3.11 (right)"}),
    "unbalanced_nodmg": ("unbalanced-force ratio against cumulative iterations, elastic and viscoelastic, no damage",
                         {"isr": "Figure 3.3 (left)", "asr-fine": "Figure 3.4 (left)", "asr-coarse": "Figure 3.5 (left)"}),
    "unbalanced_dmg": ("unbalanced-force ratio against cumulative iterations, elastic and viscoelastic, with damage",
                       {"isr": "Figure 3.9 (left)", "asr-fine": "Figure 3.10 (left)", "asr-coarse": "Figure 3.11 (left)"}),
    "forces_nodmg": ("5 % / 95 % normal-force quantiles per kind against log time with the tensile capacity f_t A; "
                     "elastic (top), viscoelastic (bottom), no damage", {"isr": "Figure 3.6", "asr-fine": "Figure 3.7", "asr-coarse": "Figure 3.8"}),
    "forces_dmg": ("the same with damage", {"isr": "Figure 3.12", "asr-fine": "Figure 3.13", "asr-coarse": "Figure 3.14"}),
}


def report_study(a):
    """tables.md, study.csv, the overlay figures and index.md from the runs in DIR; returns
    whether every run finished."""
    runs = {}
    for name in run_names():
        path = os.path.join(a.out, name, "results.json")
        if os.path.exists(path):
            try:
                runs[name] = report.load_results(path)
            except report.ResultsError as e:
                print(f"paper_study: {e}; left out of the tables", file=sys.stderr)
    ordered = {n: runs[n] for n in sorted(runs)}
    lines = report.paper_tables_md(ordered) + [""]
    csv_rows = []
    for sc in paper.SCENARIOS:
        ref = runs.get(f"{sc}-el-nodmg")
        others = [runs[f"{sc}-{k}"] for k in ("ve-nodmg", "el-dmg", "ve-dmg") if f"{sc}-{k}" in runs]
        lines.append(f"### Table 3.7 form: {report.LABEL[sc]}, variation to the elastic run without damage")
        lines.append("")
        if ref is None:
            lines += [f"(no {sc}-el-nodmg run: no reference)", ""]
            continue
        rows = report.compare(ref, others, names=[f"{sc}-el-nodmg"] + [f"{sc}-{k}" for k in ("ve-nodmg", "el-dmg", "ve-dmg")
                                                                         if f"{sc}-{k}" in runs])
        csv_rows += rows
        lines += report.compare_md(rows, f"{sc}-el-nodmg", ref)[2:] + [""]
    tables = "\n".join(lines)
    with open(os.path.join(a.out, "tables.md"), "w") as f:
        f.write(f"# The paper's Tables 3.4, 3.6 and 3.7: ours ({a.size_mm[0]:g} x {a.size_mm[1]:g} mm) and the paper's\n\n" + tables + "\n")
    if csv_rows:
        with open(os.path.join(a.out, "study.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(csv_rows[0]))
            w.writeheader()
            w.writerows(csv_rows)
    figures = []
    for sc in paper.SCENARIOS:
        have = lambda keys: [(report.run_label(runs[f"{sc}-{k}"]), runs[f"{sc}-{k}"]) for k in keys if f"{sc}-{k}" in runs]
        label = report.LABEL[sc]
        made = {}
        four = have(("el-nodmg", "ve-nodmg", "el-dmg", "ve-dmg"))
        if four:
            report.plot_strain_overlay(os.path.join(a.out, f"{sc}_strain.png"), four, f"{label}: swelling strain")
            made["strain"] = f"{sc}_strain.png"
        for d, words in (("nodmg", "no damage"), ("dmg", "with damage")):
            pair = have((f"el-{d}", f"ve-{d}"))
            if pair:
                report.plot_unbalanced_overlay(os.path.join(a.out, f"{sc}_unbalanced_{d}.png"), pair, f"{label}, {words}: convergence")
                report.plot_force_overlay(os.path.join(a.out, f"{sc}_forces_{d}.png"), pair, f"{label}, {words}: normal contact forces")
                made[f"unbalanced_{d}"], made[f"forces_{d}"] = f"{sc}_unbalanced_{d}.png", f"{sc}_forces_{d}.png"
        figures.append((sc, made))
    all_done = len(runs) == 12 and all(report.run_state(r) == "finished" for r in runs.values())
    # the tolerance the runs record (the ADR's class default unless told otherwise): stated by the runs, not here
    tols = sorted({r["tolerance"] for r in runs.values() if r.get("tolerance")})
    adr = f"ADR tolerance {', '.join(f'{t:g}' for t in tols)}" if tols else "ADR at its default tolerance"
    index = [f"# The paper's study at {a.size_mm[0]:g} x {a.size_mm[1]:g} mm", "",
             f"12 swelling tests (scripts/swelling_test.py), seed {a.seed}, {a.steps_per_decade:g} steps a decade, "
             f"{adr if a.solver == 'adr' else 'implicit solver (exact equilibria)'}. {report.size_note({'config': {'size_mm': a.size_mm}})} "
             f"{'Every run finished.' if all_done else 'Not every run finished: see the status column and the runs logs (<run>.log).'}",
             "", "Command: `" + " ".join(["/usr/bin/python3", "scripts/paper_study.py", "--size-mm", f"{a.size_mm[0]:g}", f"{a.size_mm[1]:g}",
                                           "--jobs", str(a.jobs), "--out", a.out, "--seed", str(a.seed),
                                           "--steps-per-decade", f"{a.steps_per_decade:g}", "--solver", a.solver]) + "`", "",
             "## Tables", "", tables, "", "## Figures", ""]
    for sc, made in figures:
        index += [f"### {report.LABEL[sc]}", ""]
        for key, (what, paper_fig) in FIGURES.items():
            if key in made:
                index += [f"- `{made[key]}`: {what}; the paper's {paper_fig[sc]}.", "", f"![{made[key]}]({made[key]})", ""]
        for b in paper.BEHAVIOUR_KEYS:
            name = f"{sc}-{b}-dmg"
            if os.path.exists(os.path.join(a.out, name, "crack_map.png")):
                index += [f"- `{name}/crack_map.png`: broken contacts at the end, {paper.BEHAVIOUR_WORDS[b]}; the paper's Figure 3.15 "
                          "(central line); crack_map_<day>d.png in the same folder at earlier times.", "",
                          f"![{name} crack map]({name}/crack_map.png)", ""]
        index += [f"Each run's own figures and table: `{sc}-<el|ve>-<nodmg|dmg>/` (swelling_strain.png, unbalanced.png, "
                  "force_quantiles.png, table.md).", ""]
    with open(os.path.join(a.out, "index.md"), "w") as f:
        f.write("\n".join(index) + "\n")
    return all_done


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size-mm", nargs=2, type=float, required=True, metavar=("W", "H"), help="specimen width and height [mm] (paper: 100 100)")
    ap.add_argument("--jobs", type=int, required=True, help="runs at a time, one process and one thread each [-]")
    ap.add_argument("--out", required=True, help="folder of the study (made if absent; an earlier call's folder resumes it)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the mesostructure, the same for the 12 runs [-]")
    ap.add_argument("--steps-per-decade", type=float, default=10.0, help="physical steps per decade of log time [1/decade]")
    # The study reproduces the paper, its method included; the implicit solver runs it in a fraction
    # of the time, with broken shares within the ADR's seed-to-seed spread (docs/performance.md, 1b).
    scenario.add_solver_argument(ap, default="adr")
    a = ap.parse_args(argv)
    with options.refuse_bad("paper_study.py"):  # exit status 2, as argparse's, before any work
        check(a)
    os.makedirs(a.out, exist_ok=True)
    progress = Progress(a.out, run_names())
    completed = run_all(a, progress)
    all_done = report_study(a)
    print(f"paper_study: tables and figures in {a.out}/index.md")
    if not completed:
        sys.exit("paper_study.py: stopped; call it again with the same options to go on")
    sys.exit(0 if all_done else 1)


if __name__ == "__main__":
    main(sys.argv[1:])
