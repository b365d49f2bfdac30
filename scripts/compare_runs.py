# SPDX-License-Identifier: GPL-2.0-or-later
"""Compares swelling-test runs in the form of the paper's Table 3.7: the 5 % / 95 % normal-force
quantiles and broken contacts per kind at the last step, with the variation in percent against a
reference run (e.g. elastic without damage).

  /usr/bin/python3 scripts/compare_runs.py --reference out/isr-el-nodmg out/isr-ve-nodmg out/isr-ve-dmg --out out/compare-isr
writes OUT/compare.md and OUT/compare.csv (plain Python; no YADE needed). A run that did not finish
(status failed, interrupted, or running with an old 'updated' time: the process died) is marked in
both, its numbers being those of its last step, not of the end. A missing, truncated or foreign
results.json is refused with a message naming it (exit status 1); bad options exit with 2."""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import report  # noqa: E402


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
    ref = load(a.reference)
    others = [load(d) for d in a.runs]
    bad = [o["scenario"] for o in others if o["scenario"] != ref["scenario"]]
    if bad:
        sys.exit(f"compare_runs.py: runs of scenario {bad} cannot be compared with a {ref['scenario']} reference")
    rows = report.compare(ref, others)
    states = [report.run_state(r) for r in [ref] + others]
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "compare.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fmt = lambda v: "-" if v != v else f"{round(v)}"  # NaN (no reference value) prints as "-"
    lines = [f"# {report.LABEL.get(ref['scenario'], ref['scenario'])}: normal contact forces (kN) and variation to the reference (%)", "",
             "| behaviour | damage | contact | 5 % | var. % | 95 % | var. % | broken (%) | run |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        mark = "" if r["run"] == "finished" else " †"
        lines.append(f"| {r['behaviour']}{mark} | {'yes' if r['damage'] else 'no'} | {r['kind']} | {r['fn_p05_kN']:.2f} | {fmt(r['var_p05_pct'])} | "
                     f"{r['fn_p95_kN']:.2f} | {fmt(r['var_p95_pct'])} | {r['broken']} ({r['broken_pct']:.1f}) | {r['run']} |")
    lines.append("")
    lines.append(f"Reference: {a.reference} ({ref['behaviour']}, damage {'on' if ref['damage'] else 'off'}).")
    if any(st != "finished" for st in states):
        lines.append("† not finished: the numbers are those of the run's last step done, not of the end of the test"
                     + (" (the reference too: every variation is against an unfinished run)." if states[0] != "finished" else "."))
    with open(os.path.join(a.out, "compare.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main(sys.argv[1:])
