# SPDX-License-Identifier: GPL-2.0-or-later
"""Readings of the paper's open choices, run over seeds beside its tables (swelldem.readings).

  /usr/bin/python3 scripts/readings_study.py --group asr-coarse|elastic-damage --size-mm W H --seeds S ... \
      --out DIR [--readings NAME ...] [--jobs N | --scheduler ADDRESS] [--solver implicit|adr] [--bounds-only]

asr-coarse: which contacts are the gel pockets, how far they swell, the aggregate's stiffness;
the four ASR-coarse runs (elastic and viscoelastic, with and without damage) of each reading.
elastic-damage: the strength and break rule; the ISR and ASR-fine elastic runs with damage.
Every run is scripts/swelling_test.py through swelldem.study (resumable, local or cluster
workers), in DIR/<reading>-<run>-s<seed>/.

For asr-coarse the force balance's bound comes first, from the mesostructures alone: per
reading, the fully restrained force of the median pocket and the bound on the aggregate
contacts' 5 % quantile (bounds.md; --bounds-only stops there). Then DIR/readings.md and
readings.csv: per reading, run and kind, the 5 % and 95 % quantiles and broken share, mean
(min to max) over the seeds, beside the paper's, bold where the mean is within 30 % (quantiles)
or 10 points (broken shares), and a score per reading. Exit status 0 when every run finished,
1 otherwise, 2 for bad options (before any work)."""
import argparse
import csv
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper, readings, study  # noqa: E402
from swelldem.scenario import SOLVERS, SwellingTest  # noqa: E402


def check(a):
    options.output_folder("out", a.out)
    options.integer("jobs", a.jobs, lo=1)
    for s in a.seeds:
        options.integer("seeds", s, lo=0)
    if len(set(a.seeds)) != len(a.seeds):
        options.bad("seeds", tuple(a.seeds), "distinct seeds")
    for r in a.runs:
        SwellingTest(**r.settings, out=a.out).validate()
    study.check(a.runs, a.out)


def write_bounds(a):
    b = readings.bounds(a.readings, a.size_mm, a.seeds)
    lines = [f"# Force balance: the gel pockets' fully restrained forces, {a.size_mm[0]:g} x {a.size_mm[1]:g} mm, seeds "
             + ", ".join(map(str, a.seeds)), "",
             "Before any run, from the mesostructures: a pocket's compression is at most E_c A / L x d (its particles held), so the "
             "aggregate contacts' 5 % quantile is at least the 5 % quantile of {that force on the pockets, 0 elsewhere} (xi = 1). "
             f"The paper's ASR-coarse AGG 5 % quantiles: {paper.TABLE_FORCES[('asr-coarse', 'el', 'nodmg')]['AGG']['p05']:g} kN "
             f"(elastic), {paper.TABLE_FORCES[('asr-coarse', 've', 'nodmg')]['AGG']['p05']:g} kN (viscoelastic).", "",
             "| reading | pockets | restrained force of the median pocket [kN] | bound on AGG 5 % [kN] | can reach the paper's |",
             "|---|---|---|---|---|"]
    paper_p05 = paper.TABLE_FORCES[("asr-coarse", "ve", "nodmg")]["AGG"]["p05"]
    for r, v in b.items():
        mean = lambda x: sum(x) / len(x)  # noqa: E731
        lines.append(f"| {r} | {mean(v['n']):.0f} | {mean(v['median_kN']):.1f} ({min(v['median_kN']):.1f} to {max(v['median_kN']):.1f}) | "
                     f"{mean(v['agg_p05_bound_kN']):.1f} ({min(v['agg_p05_bound_kN']):.1f} to {max(v['agg_p05_bound_kN']):.1f}) | "
                     f"{'yes' if max(v['agg_p05_bound_kN']) <= paper_p05 else 'no'} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "bounds.md"), "w") as f:
        f.write(text)
    print(text)


def write_table(a):
    rows = readings.table_rows(a.out, a.group, a.readings, a.seeds)
    lines = [f"# Readings ({a.group}) at {a.size_mm[0]:g} x {a.size_mm[1]:g} mm, seeds {', '.join(map(str, a.seeds))}, "
             f"solver {a.solver}", "",
             "Ours: mean (min to max) over the seeds; bold: the mean within 30 % of the paper's quantile or 10 points of its "
             "broken share. The paper's values are at 100 x 100 mm.", ""]
    lines += ["| reading | settings and the paper's words |", "|---|---|"]
    lines += [f"| {r} | {readings.READINGS[a.group][r][1]} |" for r in a.readings]
    lines += ["", "| reading | checks met |", "|---|---|"]
    lines += [f"| {r} | {ok} of {n} |" for r, (ok, n) in readings.score(rows).items()]
    lines += [""] + readings.table_md(rows, a.group)
    with open(os.path.join(a.out, "readings.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    flat = []
    for r in rows:
        row = {k: v for k, v in r.items() if not isinstance(v, tuple)}
        for k, v in r.items():
            if isinstance(v, tuple):
                row[f"{k}_mean"], row[f"{k}_min"], row[f"{k}_max"] = v
        flat.append(row)
    keys = sorted({k for r in flat for k in r}, key=lambda k: (k not in ("reading", "scenario", "behaviour", "damage", "kind"), k))
    with open(os.path.join(a.out, "readings.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(flat)
    print("\n".join(lines[:12 + 2 * len(a.readings)]))
    return all(r["seeds"] == len(a.seeds) for r in rows)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--group", required=True, help="asr-coarse or elastic-damage")
    ap.add_argument("--size-mm", nargs=2, type=float, required=True, metavar=("W", "H"), help="specimen width and height [mm]")
    ap.add_argument("--seeds", type=int, nargs="+", required=True, help="mesostructure seeds, every reading's runs on each [-]")
    ap.add_argument("--out", required=True, help="folder of the study (an earlier call's folder resumes it)")
    ap.add_argument("--readings", nargs="+", default=None, help="the readings to run (default: all of the group's)")
    ap.add_argument("--jobs", type=int, default=2, help="local Dask workers, one process and one thread each [-]")
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT) instead")
    ap.add_argument("--solver", default="implicit", choices=tuple(SOLVERS), help="quasi-static solver (default implicit)")
    ap.add_argument("--steps-per-decade", type=float, default=10.0, help="physical steps per decade of log time [1/decade]")
    ap.add_argument("--bounds-only", action="store_true", help="asr-coarse: write the force balance's bounds and stop")
    a = ap.parse_args(argv)
    with options.refuse_bad("readings_study.py"):  # exit status 2, as argparse's, before any work
        options.choice("group", a.group, tuple(readings.READINGS))
        a.readings = a.readings or list(readings.READINGS[a.group])
        for r in a.readings:
            options.choice("readings", r, tuple(readings.READINGS[a.group]))
        a.runs = readings.runs(a.group, a.readings, a.size_mm, a.seeds, a.solver, a.steps_per_decade)
        check(a)
    os.makedirs(a.out, exist_ok=True)
    if a.group == "asr-coarse":
        write_bounds(a)
        if a.bounds_only:
            return
    completed = study.run_study(a.runs, a.out, jobs=a.jobs, scheduler=a.scheduler, prog="readings_study")
    all_done = write_table(a)
    print(f"readings_study: {a.out}/readings.md")
    study.end("readings_study.py", completed, all_done)


if __name__ == "__main__":
    main(sys.argv[1:])
