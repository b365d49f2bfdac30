# SPDX-License-Identifier: GPL-2.0-or-later
"""Residual properties against expansion (issue 16): scripts/residual_properties.py for ISR,
ASR-fine and ASR-coarse, elastic and viscoelastic, damage on, several seeds, each tested at three
ages (about 1/3 and 2/3 of the swelling kinetics and the run's end); then one PNG and one CSV per
quantity (E/E0, ft/ft0, fc/fc0, Et/Et0, SDI, PDI) against the expansion, every seed shown.

    /usr/bin/python3 scripts/residual_study.py --size-mm 20 20 --seeds 1 2 3 --out out/residual_study
    /usr/bin/python3 scripts/residual_study.py --out out/residual_study --plots-only

Runs one YADE process at a time (scripts/yade-swelldem -j 1); a run whose residual.json exists
is not made again. The undamaged specimen's tests are shared between runs of the same seed and
age (--reference-cache of residual_properties.py).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, scenario  # noqa: E402
#: Test ages [day]: Larive's xi about 0.32 and 0.65 (tau_L, tau_c of paper.KINETICS), and the end.
AGES = {"isr": (80, 130, 3650), "asr-fine": (4000, 7000, 50000), "asr-coarse": (4000, 7000, 50000)}
SCENARIOS = ("isr", "asr-fine", "asr-coarse")
BEHAVIOURS = ("elastic", "viscoelastic")
QUANTITIES = {"E_rel": "E / E0 (compression, 5-40 % of the peak)", "fc_rel": "f_c / f_c0", "ft_rel": "f_t / f_t0 (direct tension)",
              "Et_rel": "E / E0 (tension, 5-40 % of the peak)", "SDI": "SDT stiffness damage index SDI",
              "PDI": "SDT plastic strain index PDI"}

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--size-mm", type=float, nargs=2, default=(20.0, 20.0), metavar=("W", "H"), help="specimen size [mm]")
ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3], help="mesostructure seeds")
ap.add_argument("--scenarios", nargs="+", default=list(SCENARIOS), choices=SCENARIOS)
ap.add_argument("--behaviours", nargs="+", default=list(BEHAVIOURS), choices=BEHAVIOURS)
ap.add_argument("--out", default="out/residual_study", help="output folder")
scenario.add_solver_argument(ap)
ap.add_argument("--test-options", nargs=argparse.REMAINDER, default=[],
                help="the rest of the line goes to residual_properties.py (e.g. --strain-step-tension 6e-6)")
ap.add_argument("--plots-only", action="store_true", help="only gather the runs made and plot")
args = ap.parse_args()
with options.refuse_bad("residual_study.py"):  # exit status 2, as argparse's, before any work
    options.output_folder("out", args.out)


def run_name(sc, beh, seed):
    return f"{sc}-{'el' if beh == 'elastic' else 've'}-s{seed}"


runs = [(sc, beh, seed) for sc in args.scenarios for beh in args.behaviours for seed in args.seeds]
if not args.plots_only:
    env = dict(os.environ, OMP_NUM_THREADS="1")
    for sc, beh, seed in runs:
        out = os.path.join(args.out, run_name(sc, beh, seed))
        if os.path.exists(os.path.join(out, "residual.json")):
            continue
        os.makedirs(out, exist_ok=True)
        cmd = [os.path.join(REPO, "scripts", "yade-swelldem"), "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "residual_properties.py"),
               "--scenario", sc, "--behaviour", beh, "--size-mm", *[f"{v:g}" for v in args.size_mm], "--seed", str(seed), "--solver", args.solver,
               "--test-ages", *[str(a) for a in AGES[sc]], "--reference-cache", os.path.join(args.out, "reference_cache"), "--out", out] + args.test_options
        t0 = time.time()
        with open(os.path.join(out, "log.txt"), "w") as log:
            rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
        print(f"{run_name(sc, beh, seed)}: exit {rc}, {time.time() - t0:.0f} s", flush=True)

rows = []
for sc, beh, seed in runs:
    path = os.path.join(args.out, run_name(sc, beh, seed), "residual.json")
    if not os.path.exists(path):
        continue
    with open(path) as f:
        r = json.load(f)
    for a in r["ages"]:
        if a.get("sdt_status") != "done":  # an SDT that failed before its last cycle has no indices to compare
            a = dict(a, SDI=float("nan"), PDI=float("nan"))
        rows.append({"scenario": sc, "behaviour": beh, "seed": seed, "age_days": a["age_days"], "expansion_pct": 100 * a["expansion"],
                     **{q: a.get(q, float("nan")) for q in QUANTITIES}, "SDI0": a.get("SDI0"), "PDI0": a.get("PDI0"),
                     "sdt_status": a.get("sdt_status"), "broken_before_test": a.get("broken_before_compression"),
                     "n_contacts": a.get("n_contacts"), "wall_s": r["wall_s"],
                     # the mean of the x and y strains (a residual.json without expansion_linear: from strain_x, strain_y)
                     "expansion_linear_pct": 100 * a.get("expansion_linear", 0.5 * (a["strain_x"] + a["strain_y"])),
                     "fc_lower_bound": bool(a.get("fc_lower_bound") or a.get("fc0_lower_bound"))})
if not rows:
    sys.exit("no runs found in " + args.out)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLORS = {"isr": "tab:blue", "asr-fine": "tab:red", "asr-coarse": "tab:green"}
MARKERS = {"elastic": "o", "viscoelastic": "s"}
for q, label in QUANTITIES.items():
    with open(os.path.join(args.out, f"{q}.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["scenario", "behaviour", "seed", "age_days", "expansion_pct", q, "expansion_linear_pct"])
        for r in rows:
            w.writerow([r["scenario"], r["behaviour"], r["seed"], r["age_days"], f"{r['expansion_pct']:.4f}", f"{r[q]:.4f}",
                        f"{r['expansion_linear_pct']:.4f}"])
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for sc in args.scenarios:
        for beh in args.behaviours:
            sel = [r for r in rows if r["scenario"] == sc and r["behaviour"] == beh]
            if not sel:
                continue
            x = np.array([r["expansion_pct"] for r in sel])
            y = np.array([r[q] for r in sel])
            ax.scatter(x, y, c=COLORS[sc], marker=MARKERS[beh], s=22, alpha=0.55, edgecolors="none")
            # mean of the seeds per age, with their range as error bar
            ages = sorted({r["age_days"] for r in sel})
            mx, my, lo, hi = [], [], [], []
            for a in ages:
                xa = np.array([r["expansion_pct"] for r in sel if r["age_days"] == a])
                ya = np.array([r[q] for r in sel if r["age_days"] == a])
                ok = np.isfinite(ya)
                if not ok.any():
                    continue
                mx.append(xa.mean()); my.append(ya[ok].mean()); lo.append(ya[ok].mean() - ya[ok].min()); hi.append(ya[ok].max() - ya[ok].mean())
            ax.errorbar(mx, my, yerr=[lo, hi], color=COLORS[sc], marker=MARKERS[beh], mfc="white" if beh == "viscoelastic" else COLORS[sc],
                        lw=1, capsize=3, label=f"{sc}, {beh}")
    ax.set_xlabel("expansion of the swelling run at the test age, area strain (%)")
    # laboratories report length change: the linear strain of an isotropic expansion is half the area strain
    top = ax.secondary_xaxis("top", functions=(lambda x: x / 2, lambda x: 2 * x))
    top.set_xlabel("linear expansion, area strain / 2 (%)", fontsize=8)
    ax.set_ylabel(label)
    if q.endswith("_rel"):
        ax.axhline(1.0, color="0.6", lw=0.8)
        ax.set_ylim(0, max(1.1, np.nanmax([r[q] for r in rows]) + 0.05))
    else:
        # the same test on the undamaged specimen: what the method gives without any swelling damage
        floor = np.nanmean([r[q + "0"] for r in rows if r[q + "0"] is not None])
        ax.axhline(floor, color="0.4", ls="--", lw=0.8, label=f"undamaged specimens, mean {floor:.4f}")
        ax.legend(fontsize=7)
        ax.set_ylim(bottom=min(0.0, ax.get_ylim()[0]))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title(f"{label}: {args.size_mm[0]:g} x {args.size_mm[1]:g} mm, seeds {' '.join(map(str, args.seeds))} (dots), mean and range",
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, f"{q}.png"), dpi=110)
    plt.close(fig)

with open(os.path.join(args.out, "study.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
# Means per scenario, behaviour and age (the docs' table)
with open(os.path.join(args.out, "summary.md"), "w") as f:
    f.write("| scenario | behaviour | age (d) | area expansion (%) | linear expansion (%) | E/E0 | f_c/f_c0 | f_t/f_t0 | SDI | PDI | SDT done | "
            "f_c a lower bound |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    for sc in args.scenarios:
        for beh in args.behaviours:
            for a in sorted({r["age_days"] for r in rows if r["scenario"] == sc}):
                sel = [r for r in rows if r["scenario"] == sc and r["behaviour"] == beh and r["age_days"] == a]
                if not sel:
                    continue

                def ms(k, fmt="{:.2f}"):
                    v = np.array([r[k] for r in sel], float)
                    v = v[np.isfinite(v)]
                    return (fmt.format(v.mean()) + " (" + fmt.format(v.min()) + "-" + fmt.format(v.max()) + ")") if len(v) else "-"
                done = sum(1 for r in sel if r["sdt_status"] == "done")
                low = sum(1 for r in sel if r["fc_lower_bound"])
                f.write(f"| {sc} | {beh} | {a:g} | {ms('expansion_pct', '{:.3f}')} | {ms('expansion_linear_pct', '{:.3f}')} | {ms('E_rel')} | "
                        f"{ms('fc_rel')} | {ms('ft_rel')} | {ms('SDI', '{:.3f}')} | {ms('PDI', '{:.3f}')} | {done}/{len(sel)} | {low}/{len(sel)} |\n")
print(f"wrote {len(rows)} rows, {len(QUANTITIES)} PNG and CSV into {args.out}")
