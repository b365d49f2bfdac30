# SPDX-License-Identifier: GPL-2.0-or-later
"""Reinforced swelling specimens (docs/structures.md): ISR and ASR-fine, viscoelastic, damage on,
one bar along x at mid-height with reinforcement ratios 0 (no bar), 1e-5 (the same carved
specimen with a bar of next to no stiffness: the reference of the bar's effect), 0.5, 1 and 2 %.
Writes DIR/rebar_study.csv, .md and rebar_expansion.png (expansion along and across the bar, the
bar's mean and largest stress against time with the yield stress), and each run's folder.

  scripts/yade-swelldem -j 1 -n -x scripts/rebar_study.py --size-mm 20 20 --out out/rebar"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))), "py"))
from swelldem import options, scenario  # noqa: E402

RATIOS = (0.0, 1e-5, 0.005, 0.01, 0.02)
SCENARIOS = ("isr", "asr-fine")


def parse(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size-mm", type=float, nargs=2, default=(20.0, 20.0), metavar=("W", "H"), help="specimen [mm]")
    p.add_argument("--seed", type=int, default=1, help="mesostructure seed")
    p.add_argument("--steps-per-decade", type=float, default=3.0, help="physical steps per decade [1/decade]")
    p.add_argument("--behaviour", default="viscoelastic", choices=scenario.BEHAVIOURS, help="contacts")
    p.add_argument("--out", default="out/rebar", help="output folder")
    scenario.add_solver_argument(p)
    return p.parse_args(argv)


def label(rho):
    return "no bar" if rho == 0 else ("bar without stiffness (1e-5)" if rho < 1e-4 else f"{100 * rho:g} %")


def main(argv):
    with options.refuse_bad("rebar_study.py"):
        a = parse(argv)
        options.output_folder("out", a.out)
        options.numbers("size_mm", a.size_mm, count=2, lo=0, unit="mm", allowed="two finite lengths > 0 [mm]")
        tests = {(sc, rho): scenario.SwellingTest(scenario=sc, behaviour=a.behaviour, size_mm=tuple(a.size_mm), seed=a.seed,
                                                  steps_per_decade=a.steps_per_decade, rebar_ratio=rho, solver=a.solver,
                                                  out=os.path.join(a.out, f"{sc}-rho{rho:g}"))
                 for sc in SCENARIOS for rho in RATIOS}
        for t in tests.values():
            t.validate()
    os.makedirs(a.out, exist_ok=True)
    results = scenario.run_all(tests, "rebar_study")
    write(a.out, results)


def write(out, results):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = []
    for (sc, rho), r in results.items():
        if not r["times_days"]:
            continue
        bar = r.get("rebar", {})
        rows.append({"scenario": sc, "ratio": rho, "status": r["status"].split(":")[0],
                     "strain_along_1e-6": 1e6 * r["swelling_strain_x"][-1], "strain_across_1e-6": 1e6 * r["swelling_strain_y"][-1],
                     "strain_area_1e-6": 1e6 * r["swelling_strain_area"][-1],
                     "bar_stress_mean_MPa": r["rebar_stress_mean_Pa"][-1] / 1e6 if bar else "",
                     "bar_stress_max_MPa": r["rebar_stress_max_Pa"][-1] / 1e6 if bar else "",
                     "yield_day": bar.get("yield_day") if bar else "",
                     "broken_MORTAR": r["per_kind"]["MORTAR"]["broken"][-1], "broken_ITZ": r["per_kind"]["ITZ"]["broken"][-1]})
    with open(os.path.join(out, "rebar_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| scenario | ratio | run | along the bar [1e-6] | across [1e-6] | area [1e-6] | bar stress mean / max [MPa] | yield (f_y 500 MPa) day | broken MORTAR / ITZ |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        stress = f"{r['bar_stress_mean_MPa']:.0f} / {r['bar_stress_max_MPa']:.0f}" if r["bar_stress_mean_MPa"] != "" else "-"
        yd = "-" if r["yield_day"] in ("", None) else f"{r['yield_day']:.0f}"
        lines.append(f"| {r['scenario']} | {label(r['ratio'])} | {r['status']} | {r['strain_along_1e-6']:.0f} | {r['strain_across_1e-6']:.0f} | "
                     f"{r['strain_area_1e-6']:.0f} | {stress} | {yd} | {r['broken_MORTAR']} / {r['broken_ITZ']} |")
    with open(os.path.join(out, "rebar_study.md"), "w") as f:
        f.write("Final values (last step); strains of the skeleton's affine fit, bar along x.\n\n" + "\n".join(lines) + "\n")

    fig, axes = plt.subplots(len(SCENARIOS), 3, figsize=(14, 3.6 * len(SCENARIOS)), squeeze=False)
    cmap = plt.get_cmap("viridis")
    for i, sc in enumerate(SCENARIOS):
        for n, rho in enumerate(RATIOS):
            r = results.get((sc, rho))
            if not r or not r["times_days"]:
                continue
            t = np.array(r["times_days"])
            color = "k" if rho == 0 else cmap(n / len(RATIOS))
            ls = ":" if rho == 0 else "-"
            axes[i, 0].semilogx(t, 1e6 * np.array(r["swelling_strain_x"]), ls, color=color, label=label(rho))
            axes[i, 1].semilogx(t, 1e6 * np.array(r["swelling_strain_y"]), ls, color=color, label=label(rho))
            if rho > 0:
                axes[i, 2].semilogx(t, np.array(r["rebar_stress_mean_Pa"]) / 1e6, "-", color=color, label=f"{label(rho)}: mean")
                axes[i, 2].semilogx(t, np.array(r["rebar_stress_max_Pa"]) / 1e6, "--", color=color, lw=0.8, label=f"{label(rho)}: largest")
                fy = r["rebar"]["yield_stress_Pa"] / 1e6
        axes[i, 2].axhline(fy, color="tab:red", lw=0.8, label="yield stress f_y")
        axes[i, 0].set(title=f"{sc}: expansion along the bar (x)", xlabel="time [day]", ylabel="strain [1e-6]")
        axes[i, 1].set(title=f"{sc}: expansion across the bar (y)", xlabel="time [day]", ylabel="strain [1e-6]")
        axes[i, 2].set(title=f"{sc}: bar stress (tension > 0)", xlabel="time [day]", ylabel="stress [MPa]")
        for ax in axes[i]:
            ax.grid(True, which="both", lw=0.3)
        axes[i, 0].legend(fontsize=7, title="reinforcement ratio", title_fontsize=7)
        axes[i, 2].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "rebar_expansion.png"), dpi=110)
    plt.close(fig)
    print(f"rebar_study: tables and plots in {out}/")


main(sys.argv[1:])
