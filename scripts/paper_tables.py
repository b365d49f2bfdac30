# SPDX-License-Identifier: GPL-2.0-or-later
"""Our swelling-test runs next to the paper's Tables 3.4 and 3.6 (forces without and with damage).

  /usr/bin/python3 scripts/paper_tables.py out/paper40 > out/paper40/paper_tables.md

reads DIR/*/results.json, the runs of scripts/swelling_test.py that scripts/paper_study.py puts in
DIR/<scenario>-<el|ve>-<nodmg|dmg>/, and prints Markdown tables: for each run and contact kind,
our 5 % / 95 % normal-force quantiles [kN], the variation of the viscoelastic run to the elastic
one [%] and broken contacts (%) beside the paper's (swelldem.paper.TABLE_FORCES, VARIATION). Each
run's scenario, behaviour and damage are those its results.json records, whatever its folder's
name (a folder named otherwise is shown beside the run's name); a results.json without them is
not a swelling test's and is refused. Runs that did not finish (failed, interrupted, or 'running'
with an old update time: the process died) are marked with how they ended. Refused with a message
naming the files (exit status 1), before anything is printed: a truncated, malformed or foreign
results.json, two runs of the same scenario, behaviour and damage, and a folder without any run."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import report  # noqa: E402

USAGE = "a folder of swelling-test runs, one per subfolder <run>/results.json (scripts/paper_study.py --out)"


def load(path):
    try:
        return report.load_results(path)
    except report.ResultsError as e:
        sys.exit(f"paper_tables.py: {e}")


def study_runs(folder):
    """({run_key: results dict}, {run_key: folder name}) of the runs in `folder`, keyed by what
    each results.json says; every results.json is read (and refused if malformed) first. Exits
    with status 1 and one line for a folder without runs or two runs of the same key."""
    if not os.path.isdir(folder):
        sys.exit(f"paper_tables.py: folder = {folder!r} is not a folder; allowed: {USAGE}")
    runs, folders = {}, {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "results.json")
        if not (os.path.isdir(os.path.join(folder, name)) and os.path.exists(path)):
            continue
        res = load(path)
        key = report.run_key(res)
        if key is None:
            sys.exit(f"paper_tables.py: {path}: a run the paper has no counterpart of (scenario {res['scenario']!r}, "
                     f"behaviour {res['behaviour']!r}); allowed: {USAGE} of the paper's scenarios and behaviours")
        if key in runs:
            sys.exit(f"paper_tables.py: {os.path.join(folder, folders[key], 'results.json')} and {path} are both runs of {key} "
                     f"({res['scenario']}, {res['behaviour']}, damage {'on' if res['damage'] else 'off'}); allowed: one run of each "
                     "scenario, behaviour and damage in a folder")
        runs[key], folders[key] = res, name
    if not runs:
        sys.exit(f"paper_tables.py: folder = {folder!r} holds no run (no <run>/results.json); allowed: {USAGE}")
    return {k: runs[k] for k in sorted(runs)}, folders


def main(folder):
    runs, folders = study_runs(folder)
    print("\n".join(report.paper_tables_md(runs, folders)))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
