# SPDX-License-Identifier: GPL-2.0-or-later
"""A study: the swelling tests of a table, each over seeds, on Dask distributed.

  /usr/bin/python3 scripts/study.py --table FILE --out DIR [--seeds S ...] [--jobs N | --scheduler ADDRESS]

FILE is a table in yade-batch's form (scripts/swelling_sweep.table): a header of SwellingTest
field names (swelling_test.py --help, with _ for -), one run a line, values Python literals
without blanks ('isr' quoted, (40,40), {'MORTAR':{'tensileStrength':5e6}}), '=' for the value of
the line above, a 'description' column naming the run's folder. --seeds runs every line once a
seed (folders <description>-s<seed>; a table with a seed column takes no --seeds).

Without --scheduler the runs go to a local Dask cluster of N worker processes (one thread each);
with --scheduler tcp://HOST:PORT to a running Dask scheduler and its workers (started with
scripts/study-worker ADDRESS where the project is set up at the same path and DIR is reachable
at the same path; docs/guide.md, "Studies on a cluster"). Each run is scripts/swelling_test.py in
its own process, DIR/<run>/ and its log DIR/<run>.log.

Resumable: a run that finished with the same settings is kept, any other runs again; a finished
run of other settings in DIR stops the study before any work. A run whose worker died runs again
on another worker. Ctrl-C or SIGTERM stops the running runs (they record 'interrupted'); the next
call goes on from there.

DIR then holds runs.json and runs.md (per run: state, worker, host, wall time, attempts),
progress.md, and summary.md / summary.csv: per table line the final strains, broken shares and
force quantiles, mean and min-max over its seeds. Exit status 0 when every run finished, 1 when
one did not, 2 for bad options (before any work)."""
import argparse
import csv
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, study  # noqa: E402


def write_summary(out, runs, seeds):
    rows = study.summary_rows(out, runs)
    measures = [(k, head) for k, head in study.MEASURES if any(f"{k}_mean" in r for r in rows)]
    keys = ["run", "seeds", "finished"] + [f"{k}_{s}" for k, _ in measures for s in ("mean", "min", "max")]
    with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)

    def cell(r, k):
        if f"{k}_mean" not in r:
            return ""
        lo, mean, hi = r[f"{k}_min"], r[f"{k}_mean"], r[f"{k}_max"]
        return f"{mean:.4g}" if r["finished"] == 1 else f"{mean:.4g} ({lo:.4g} to {hi:.4g})"

    lines = [f"# Study summary: {len(runs)} runs" + (f", seeds {' '.join(map(str, seeds))}" if seeds else ""), "",
             "Final values of each line's finished runs: with several seeds, their mean and (min to max).", "",
             "| run | finished / seeds | " + " | ".join(h for _, h in measures) + " |", "|---|---|" + "---|" * len(measures)]
    for r in rows:
        lines.append(f"| {r['run']} | {r['finished']} / {r['seeds']} | " + " | ".join(cell(r, k) for k, _ in measures) + " |")
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--table", required=True, help="table of runs (yade-batch's form)")
    ap.add_argument("--out", required=True, help="folder of the study (made if absent; an earlier call's folder resumes it)")
    ap.add_argument("--seeds", type=int, nargs="+", default=None, help="run every line once a seed [-]")
    ap.add_argument("--jobs", type=int, default=1, help="local Dask workers, one process and one thread each, without --scheduler [-]")
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT) whose workers run the study")
    a = ap.parse_args(argv)
    with options.refuse_bad("study.py"):  # exit status 2, as argparse's, before any work
        options.integer("jobs", a.jobs, lo=1)
        runs = study.read_table(a.table)
        if a.seeds:
            runs = study.with_seeds(runs, a.seeds)
        study.check(runs, a.out)
    completed = study.run_study(runs, a.out, jobs=a.jobs, scheduler=a.scheduler, prog="study.py")
    write_summary(a.out, runs, a.seeds)
    states = study.results_state(a.out, runs)
    print(f"study.py: {sum(s == 'finished' for s in states.values())} of {len(runs)} runs finished; {a.out}/summary.md, runs.md")
    study.end("study.py", completed, all(s == "finished" for s in states.values()))


if __name__ == "__main__":
    main(sys.argv[1:])
