# SPDX-License-Identifier: GPL-2.0-or-later
"""Our swelling-test runs next to the paper's Tables 3.4 and 3.6 (forces without and with damage).

  /usr/bin/python3 scripts/paper_tables.py out/paper40 > out/paper40/paper_tables.md

expects DIR/<scenario>-<el|ve>-<nodmg|dmg>/results.json for scenario in isr, asr-fine, asr-coarse
(the runs listed in docs/scenarios.md) and prints Markdown tables: for each run and contact kind,
our 5 % / 95 % normal-force quantiles [kN] and broken contacts (%) beside the paper's. Runs that did
not finish (failed, interrupted, or 'running' with an old update time: the process died) are marked
with how they ended; a truncated, malformed or foreign results.json is refused with a message
naming it (exit status 1), before anything is printed."""
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
    unfinished = False
    for damage, title in (("nodmg", "without damage (paper Table 3.4)"), ("dmg", "with damage (paper Table 3.6)")):
        print(f"### Normal contact forces {title}\n")
        print("| analysis | behaviour | contact | 5 % ours | 5 % paper | 95 % ours | 95 % paper | broken % ours | broken % paper |")
        print("|---|---|---|---|---|---|---|---|---|")
        for sc in ("isr", "asr-fine", "asr-coarse"):
            for beh in ("el", "ve"):
                res = runs.get(f"{sc}-{beh}-{damage}")
                if res is None:
                    print(f"| {report.LABEL[sc]} | {BEHAVIOUR[beh]} | (not run) | | | | | | |")
                    continue
                state = report.run_state(res)
                # a run that did not finish shows its last step's numbers, marked with how it ended
                mark = "" if state == "finished" else f" ({state}) †"
                unfinished |= bool(mark)
                rows = {r["kind"]: r for r in report.final_rows(res)}
                for kind in ("MORTAR", "ITZ", "AGG"):
                    p = PAPER[(sc, beh, damage)][kind]
                    r = rows[kind]
                    paper_broken = f"{p[2]:.1f}" if len(p) > 2 else "0"
                    print(f"| {report.LABEL[sc]} | {BEHAVIOUR[beh]}{mark} | {kind} | {r['fn_p05_kN']:.2f} | {p[0]:.1f} | {r['fn_p95_kN']:.2f} | "
                          f"{p[1]:.1f} | {r['broken_pct']:.1f} | {paper_broken} |")
        print()
    if unfinished:
        print("† not finished: the numbers are those of the run's last step done, not of the end of the test.\n")
    print("Broken: contacts bonded at the start that broke; contacts made during the run (born broken) are not counted.\n")
    print("### Runs\n")
    print("| run | particles | contacts | final strain x, y (1e-6) | iterations | wall (s) | last step (day) | new contacts | status |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, r in runs.items():
        sx, sy = (r["swelling_strain_x"] or [float("nan")])[-1], (r["swelling_strain_y"] or [float("nan")])[-1]
        born = [row["born_broken"] for row in report.final_rows(r)]
        born = "-" if None in born else str(sum(born))
        t_last = f"{r['times_days'][-1]:g}" if r["times_days"] else "-"
        print(f"| {name} | {r.get('n_particles', '?')} | {sum(r['n_contacts_by_kind'].values())} | {sx * 1e6:.0f}, {sy * 1e6:.0f} | "
              f"{r.get('adr_iterations', '?')} | {r.get('wall_s', float('nan')):.0f} | {t_last} | {born} | {report.run_state(r)[:60]} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
