# SPDX-License-Identifier: GPL-2.0-or-later
"""Compares swelling-test runs in the form of the paper's Table 3.7: the 5 % / 95 % normal-force
quantiles and broken contacts per kind at the last step, with the variation in percent against a
reference run (e.g. elastic without damage), the paper's values beside ours where the paper has
the same runs, and the runs on common figures, each run in its own colour, its legend and compare.md
naming the settings in which the runs differ.

  /usr/bin/python3 scripts/compare_runs.py --reference out/isr-el-nodmg out/isr-ve-nodmg out/isr-ve-dmg --out out/compare-isr
writes OUT/compare.md, OUT/compare.csv and the overlays OUT/compare_strain.png (swelling strain
against log time with the free swelling), OUT/compare_unbalanced.png (unbalanced-force ratio
against cumulative iterations) and OUT/compare_forces.png (one row of per-kind force quantiles per
run) (plain Python; no YADE needed). A run that did not finish (status failed, interrupted, or
running with an old 'updated' time: the process died) is marked in both tables, its numbers being
those of its last step, not of the end. A missing, truncated or foreign results.json is refused
with a message naming it (exit status 1); bad options exit with 2."""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import options, report  # noqa: E402


def load(d):
    try:
        return report.load_results(os.path.join(d, "results.json"))
    except report.ResultsError as e:
        sys.exit(f"compare_runs.py: {e}")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", required=True, help="run folder of the reference behaviour")
    ap.add_argument("runs", nargs="+", help="run folders to compare with it")
    ap.add_argument("--out", default="out/compare")
    a = ap.parse_args(argv)
    with options.refuse_bad("compare_runs.py"):
        options.output_folder("out", a.out)
    ref = load(a.reference)
    others = [load(d) for d in a.runs]
    bad = [o["scenario"] for o in others if o["scenario"] != ref["scenario"]]
    if bad:
        sys.exit(f"compare_runs.py: runs of scenario {bad} cannot be compared with a {ref['scenario']} reference")
    rows = report.compare(ref, others, names=[os.path.basename(os.path.normpath(d)) for d in [a.reference] + a.runs])
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "compare.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    folders = [os.path.basename(os.path.normpath(d)) for d in [a.reference] + a.runs]
    lines = report.compare_md(rows, a.reference, ref, runs=list(zip(folders, [ref] + others)))
    differ = report.differing_settings([ref] + others)
    runs = [(f"{name}: {report.run_label(r, differ)}", r) for name, r in zip(folders, [ref] + others)]
    names = report.write_overlays(a.out, runs, "compare", report.LABEL.get(ref["scenario"], ref["scenario"]))
    lines += ["", "Figures: " + ", ".join(names) + "."]
    with open(os.path.join(a.out, "compare.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1:])
