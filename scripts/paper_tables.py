# SPDX-License-Identifier: GPL-2.0-or-later
"""Our swelling-test runs next to the paper's Tables 3.4 and 3.6 (forces without and with damage).

  /usr/bin/python3 scripts/paper_tables.py out/paper40 > out/paper40/paper_tables.md

expects DIR/<scenario>-<el|ve>-<nodmg|dmg>/results.json for scenario in isr, asr-fine, asr-coarse
(the runs scripts/paper_study.py makes) and prints Markdown tables: for each run and contact kind,
our 5 % / 95 % normal-force quantiles [kN], the variation of the viscoelastic run to the elastic
one [%] and broken contacts (%) beside the paper's (swelldem.paper.TABLE_FORCES, VARIATION). Runs
that did not finish (failed, interrupted, or 'running' with an old update time: the process died)
are marked with how they ended; a truncated, malformed or foreign results.json is refused with a
message naming it (exit status 1), before anything is printed."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import report  # noqa: E402


def load(path):
    try:
        return report.load_results(path)
    except report.ResultsError as e:
        sys.exit(f"paper_tables.py: {e}")


def main(folder):
    if not os.path.isdir(folder):
        sys.exit(f"paper_tables.py: folder = {folder!r} is not a folder; allowed: a folder of runs <scenario>-<el|ve>-<nodmg|dmg>/")
    # every results.json is read (and refused if malformed) before anything is printed
    runs = {}
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "results.json")
        if os.path.isdir(os.path.join(folder, name)) and os.path.exists(path):
            runs[name] = load(path)
    print("\n".join(report.paper_tables_md(runs)))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
