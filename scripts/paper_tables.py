# SPDX-License-Identifier: GPL-2.0-or-later
"""Our swelling-test runs next to the paper's Tables 3.4 and 3.6 (forces without and with damage).

  /usr/bin/python3 scripts/paper_tables.py out/paper40 > out/paper40/paper_tables.md

expects DIR/<scenario>-<el|ve>-<nodmg|dmg>/results.json for scenario in isr, asr-fine, asr-coarse
(the runs listed in docs/scenarios.md) and prints Markdown tables: for each run and contact kind,
our 5 % / 95 % normal-force quantiles [kN] and broken contacts (%) beside the paper's."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import report  # noqa: E402

# Paper Table 3.4 (no damage): (5 %, 95 %) [kN]; Table 3.6 (damage): (5 %, 95 %, broken %).
PAPER = {
    ("isr", "el", "nodmg"): {"MORTAR": (-8.3, 2.5), "ITZ": (-3.7, 6.3), "AGG": (0.0, 8.4)},
    ("isr", "ve", "nodmg"): {"MORTAR": (-2.0, 0.6), "ITZ": (-1.6, 1.9), "AGG": (-0.5, 3.1)},
    ("asr-fine", "el", "nodmg"): {"MORTAR": (-13.5, 3.8), "ITZ": (-1.6, 0.6), "AGG": (0.5, 1.2)},
    ("asr-fine", "ve", "nodmg"): {"MORTAR": (-3.4, 1.0), "ITZ": (-0.7, 3.3), "AGG": (-0.2, 3.7)},
    ("asr-coarse", "el", "nodmg"): {"MORTAR": (-1.9, 3.6), "ITZ": (-8.6, 4.6), "AGG": (-55.4, 30.7)},
    ("asr-coarse", "ve", "nodmg"): {"MORTAR": (-0.7, 1.1), "ITZ": (-3.2, 1.9), "AGG": (-47.7, 31.8)},
    ("isr", "el", "dmg"): {"MORTAR": (-1.5, 1.4, 12.4), "ITZ": (0.0, 0.0, 90.3), "AGG": (-0.4, 0.5, 16.2)},
    ("isr", "ve", "dmg"): {"MORTAR": (-1.1, 0.7, 0.4), "ITZ": (-0.7, 0.8, 68.3), "AGG": (-0.7, 1.6, 2.3)},
    ("asr-fine", "el", "dmg"): {"MORTAR": (-1.6, 1.5, 13.6), "ITZ": (0.0, 0.0, 98.5), "AGG": (0.0, 0.0, 6.2)},
    ("asr-fine", "ve", "dmg"): {"MORTAR": (-0.7, 0.6, 1.1), "ITZ": (-0.1, 0.3, 85.9), "AGG": (-0.3, 0.7, 2.9)},
    ("asr-coarse", "el", "dmg"): {"MORTAR": (-0.4, 0.4, 21.3), "ITZ": (-0.3, 0.2, 61.4), "AGG": (-0.5, 0.5, 31.5)},
    ("asr-coarse", "ve", "dmg"): {"MORTAR": (-0.6, 0.9, 7.7), "ITZ": (-1.4, 0.6, 37.0), "AGG": (-1.9, 1.1, 30.8)},
}
BEHAVIOUR = {"el": "elastic", "ve": "aging viscoelastic"}


def main(folder):
    for damage, title in (("nodmg", "without damage (paper Table 3.4)"), ("dmg", "with damage (paper Table 3.6)")):
        print(f"### Normal contact forces {title}\n")
        print("| analysis | behaviour | contact | 5 % ours | 5 % paper | 95 % ours | 95 % paper | broken % ours | broken % paper |")
        print("|---|---|---|---|---|---|---|---|---|")
        for sc in ("isr", "asr-fine", "asr-coarse"):
            for beh in ("el", "ve"):
                path = os.path.join(folder, f"{sc}-{beh}-{damage}", "results.json")
                if not os.path.exists(path):
                    print(f"| {report.LABEL[sc]} | {BEHAVIOUR[beh]} | (not run) | | | | | | |")
                    continue
                with open(path) as f:
                    res = json.load(f)
                rows = {r["kind"]: r for r in report.final_rows(res)}
                for kind in ("MORTAR", "ITZ", "AGG"):
                    p = PAPER[(sc, beh, damage)][kind]
                    r = rows[kind]
                    paper_broken = f"{p[2]:.1f}" if len(p) > 2 else "0"
                    print(f"| {report.LABEL[sc]} | {BEHAVIOUR[beh]} | {kind} | {r['fn_p05_kN']:.2f} | {p[0]:.1f} | {r['fn_p95_kN']:.2f} | "
                          f"{p[1]:.1f} | {r['broken_pct']:.1f} | {paper_broken} |")
        print()
    print("### Runs\n")
    print("| run | particles | contacts | final strain x, y (1e-6) | ADR iterations | wall (s) | status |")
    print("|---|---|---|---|---|---|---|")
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "results.json")
        if os.path.isdir(os.path.join(folder, name)) and os.path.exists(path):
            with open(path) as f:
                r = json.load(f)
            sx, sy = (r["swelling_strain_x"] or [float("nan")])[-1], (r["swelling_strain_y"] or [float("nan")])[-1]
            print(f"| {name} | {r['n_particles']} | {sum(r['n_contacts_by_kind'].values())} | {sx * 1e6:.0f}, {sy * 1e6:.0f} | "
                  f"{r['adr_iterations']} | {r['wall_s']:.0f} | {r['status'][:40]} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
