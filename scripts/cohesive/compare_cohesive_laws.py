# SPDX-License-Identifier: GPL-2.0-or-later
"""The same generated concrete specimen under swelldem's law (elastic-brittle: creep and swelling
off) and YADE's stock cohesive laws (CohFrictPhys, JCFpmPhys matched per contact; CpmPhys
calibrated to the same macroscopic modulus and tensile peak), in quasi-static uniaxial tension and
compression (issue 8; docs/cohesive-laws.md).

  scripts/yade-swelldem -j 1 -n -x scripts/cohesive/compare_cohesive_laws.py [--size-mm 15 15] [--seed 2] \
      [--deps 1e-8] [--damping 0.6] [--beta B] [--laws swelldem cohfrict jcfpm cpm] \
      [--cases tension compression swelling] [--rate-check] --out DIR

writes DIR/results.json (per law and case: modulus, peak stress, strain at peak, broken contacts
per kind at the peak and at the end, wall time, curves), DIR/table.md, DIR/table.csv,
DIR/stress_strain.png and DIR/crack_<law>_<case>.png; the free-swelling case adds DIR/swelling.csv, a
section of DIR/table.md and DIR/crack_<law>_swelling-dmg.png."""
import argparse
import csv
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(sys.argv[0]))
sys.path[:0] = [HERE, os.path.join(os.path.dirname(os.path.dirname(HERE)), "py")]
import numpy as np  # noqa: E402

import cohesive_laws as cc  # noqa: E402  (the study, beside this script)
from swelldem import meso, options, scenario  # noqa: E402
from swelldem.paper import KIND_NAMES, TENSILE_STRENGTH  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--size-mm", type=float, nargs=2, default=(15.0, 15.0), metavar=("W", "H"))
ap.add_argument("--seed", type=int, default=2, help="mesostructure seed (15 x 15 mm: seeds 2, 4, 6, 7 place the aggregates)")
ap.add_argument("--deps", type=float, default=1e-8, help="strain increment per step [-]")
ap.add_argument("--damping", type=float, default=0.6, help="NewtonIntegrator local damping [-]")
ap.add_argument("--beta", type=float, default=0.0, help="E_macro / E_c (0: measure it, scenario.calibrate_modulus_factor)")
ap.add_argument("--laws", nargs="+", choices=cc.LAWS, default=list(cc.LAWS))
ap.add_argument("--cases", nargs="+", choices=("tension", "compression", "swelling"), default=["tension", "compression", "swelling"],
                help="swelling: free swelling of the mortar (ISR kinetics, eps_inf --eps-inf), damage off and on; "
                     "swelldem by its own law, cohfrict and jcfpm by growing the mortar discs' radii (Cpm: not run)")
ap.add_argument("--eps-inf", type=float, default=1000e-6, help="free-swelling case: ultimate swelling strain of the mortar [-]")
ap.add_argument("--max-strain-compression", type=float, default=1.5e-3)
ap.add_argument("--rate-check", action="store_true", help="also run swelldem and cpm in tension at half the rate")
ap.add_argument("--out", default="out/cohesive_laws")
with options.refuse_bad("compare_cohesive_laws.py"):  # every option before any work (NaN, infinity), exit 2
    args = ap.parse_args(sys.argv[1:])
    options.output_folder("out", args.out)
    options.numbers("size_mm", args.size_mm, count=2, lo=0, allowed="two finite lengths > 0 [mm] (15 x 15 mm or more places the aggregates)")
    options.integer("seed", args.seed, lo=0)
    options.number("deps", args.deps, lo=0, hi=1e-4, allowed="0 < deps < 1e-4 [-] (a quasi-static strain step)")
    options.number("damping", args.damping, lo=0, hi=1, lo_incl=True)
    options.number("beta", args.beta, lo=0, lo_incl=True, allowed="0 (measure it) or a finite beta > 0")
    options.number("eps_inf", args.eps_inf, lo=0)
    options.number("max_strain_compression", args.max_strain_compression, lo=0)
os.makedirs(args.out, exist_ok=True)
t_start = time.time()


def log(msg):
    print(f"[{time.time() - t_start:7.1f} s] {msg}", flush=True)


assembly = meso.generate(seed=args.seed, width_mm=args.size_mm[0], height_mm=args.size_mm[1])
assembly.save(os.path.join(args.out, "assembly.npz"))
summary = assembly.summary()
log(f"specimen {args.size_mm[0]:g} x {args.size_mm[1]:g} mm, seed {args.seed}: {assembly.n_particles} discs, "
    f"{assembly.n_contacts} contacts {summary['contacts_by_kind']}")
if args.beta > 0:
    cal = {"beta": args.beta, "given": True}
else:
    cal = scenario.calibrate_modulus_factor(shear_ratio=cc.SHEAR_RATIO)
    log(f"beta = {cal['beta']:.4f} (calibrate_modulus_factor, mortar 15 x 15 mm, seed 11)")
moduli = cc.contact_moduli(cal["beta"])
res = {"config": vars(args), "calibration": cal, "contact_moduli_Pa": moduli, "tensile_strength_Pa": TENSILE_STRENGTH,
       "assembly": {k: summary[k] for k in ("n_particles", "n_contacts", "contacts_by_kind", "aggregate_area_fraction")},
       "runs": {}}


def save():
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(res, f, indent=1, default=float)


def run(law, case, deps, cpm=None):
    info = cc.build(law, assembly, moduli, damping=args.damping, cpm=cpm)
    kw = {} if case == "tension" else {"max_strain": args.max_strain_compression, "drop": 0.7}
    r = cc.run_uniaxial(law, assembly, info, case, deps_per_step=deps, **kw)
    log(f"{law:9s} {case:11s} E {r['modulus_Pa'] / 1e9:6.2f} GPa  peak {r['peak_stress_Pa'] / 1e6:6.3f} MPa at "
        f"{r['strain_at_peak'] * 1e6:6.1f}e-6  broken at peak {r['broken_at_peak']['total']:3d}, end {r['broken_end']['total']:3d} "
        f"({r['status']}, {r['steps']} steps, {r['wall_s']:.1f} s)")
    return r


uniaxial = [c for c in args.cases if c != "swelling"]
tension_ref = None
for law in [x for x in cc.LAWS if x in args.laws and x != "cpm"]:
    for case in uniaxial:
        r = run(law, case, args.deps)
        res["runs"][f"{law}/{case}"] = r
        if law == "swelldem" and case == "tension":
            tension_ref = r
        save()
if "cpm" in args.laws and uniaxial:
    if tension_ref is None:
        tension_ref = run("swelldem", "tension", args.deps)
    t0 = time.time()
    p = cc.calibrate_cpm(assembly, moduli, tension_ref["modulus_Pa"], tension_ref["peak_stress_Pa"], args.deps, args.damping, log=log)
    p["wall_s"] = time.time() - t0
    res["cpm_calibration"] = p
    for case in uniaxial:
        res["runs"][f"cpm/{case}"] = run("cpm", case, args.deps, cpm=p)
        save()
if "swelling" in args.cases:
    res["swelling"] = {}
    for damage in (False, True):
        for law in [x for x in ("swelldem", "cohfrict", "jcfpm") if x in args.laws]:
            # with damage, sliding broken contacts keep the ADR ratio near 1e-6 on this specimen
            r = cc.free_swelling(law, assembly, moduli, eps_inf=args.eps_inf, damage=damage, tolerance=1e-5 if damage else 1e-6, log=log)
            res["swelling"][f"{law}/{'dmg' if damage else 'nodmg'}"] = r
            save()
if args.rate_check:
    res["rate_check"] = {}
    for law in [x for x in ("swelldem", "cpm") if x in args.laws]:
        r = run(law, "tension", args.deps / 2, cpm=res.get("cpm_calibration"))
        full = res["runs"][f"{law}/tension"]
        res["rate_check"][law] = {"deps": args.deps / 2, "peak_stress_Pa": r["peak_stress_Pa"], "strain_at_peak": r["strain_at_peak"],
                                  "modulus_Pa": r["modulus_Pa"], "peak_change_pct": 100 * (r["peak_stress_Pa"] / full["peak_stress_Pa"] - 1),
                                  "wall_s": r["wall_s"]}
        log(f"rate check {law}: half rate changes the peak by {res['rate_check'][law]['peak_change_pct']:+.2f} %")
        save()

# ---- tables and plots ----
rows = []
for key, r in (res["runs"].items() if uniaxial else ()):
    law, case = key.split("/")
    bp, be = r["broken_at_peak"], r["broken_end"]
    rows.append({"law": law, "case": case, "modulus_GPa": r["modulus_Pa"] / 1e9, "peak_MPa": r["peak_stress_Pa"] / 1e6,
                 "strain_at_peak_1e-6": r["strain_at_peak"] * 1e6,
                 "first_break_strain_1e-6": r["first_break"]["strain"] * 1e6 if r["first_break"] else float("nan"),
                 "broken_peak_MORTAR": bp["MORTAR"], "broken_peak_ITZ": bp["ITZ"], "broken_peak_AGG": bp["AGG"],
                 "broken_end_MORTAR": be["MORTAR"], "broken_end_ITZ": be["ITZ"], "broken_end_AGG": be["AGG"],
                 "damaged_end": r["damaged_end"] if r["damaged_end"] is not None else "", "end_strain_1e-6": r["strain"][-1] * 1e6,
                 "steps": r["steps"], "wall_s": r["wall_s"], "n_contacts": r["n_contacts"]})
if rows:
    with open(os.path.join(args.out, "table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
lines = [f"# Same specimen, four cohesive laws ({args.size_mm[0]:g} x {args.size_mm[1]:g} mm, seed {args.seed}, "
         f"{assembly.n_particles} discs, {assembly.n_contacts} bonded contacts, beta {cal['beta']:.4f}, "
         f"strain step {args.deps:g}, damping {args.damping:g})", "",
         "| law | case | E (GPa) | peak (MPa) | strain at peak (1e-6) | first break at (1e-6) | broken at peak M/I/A | broken at end M/I/A | end strain (1e-6) | steps | wall (s) |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    dmg = f" (damaged {r['damaged_end']})" if r["damaged_end"] != "" else ""
    lines.append(f"| {cc.LAW_TITLES[r['law']]} | {r['case']} | {r['modulus_GPa']:.2f} | {r['peak_MPa']:.3f} | {r['strain_at_peak_1e-6']:.1f} | "
                 f"{r['first_break_strain_1e-6']:.1f} | {r['broken_peak_MORTAR']}/{r['broken_peak_ITZ']}/{r['broken_peak_AGG']} | "
                 f"{r['broken_end_MORTAR']}/{r['broken_end_ITZ']}/{r['broken_end_AGG']}{dmg} | {r['end_strain_1e-6']:.0f} | {r['steps']} | {r['wall_s']:.1f} |")
if "cpm_calibration" in res:
    p = res["cpm_calibration"]
    lines += ["", f"Cpm material: young {p['young']:.4g} Pa, epsCrackOnset {p['epsCrackOnset']:.4g}, sigmaT {p['sigmaT']:.4g} Pa ({cc.CPM_SIGMA_T_RATIO:.3g} x young x epsCrackOnset), "
                  f"relDuctility {cc.CPM_REL_DUCTILITY:g}, poisson (ks/kn) {cc.SHEAR_RATIO}; calibration {p['wall_s']:.0f} s. "
                  f"A Cpm contact counts as broken when omega > {cc.CPM_OMEGA_BROKEN}."]
if "rate_check" in res:
    for law, d in res["rate_check"].items():
        lines.append(f"Rate check ({law}, tension, strain step {d['deps']:g}): peak {d['peak_stress_Pa'] / 1e6:.3f} MPa, "
                     f"change {d['peak_change_pct']:+.2f} %.")
if res.get("swelling"):
    srows = []
    ref = {d: np.array(res["swelling"][f"swelldem/{d}"]["fn_N"]) for d in ("nodmg", "dmg") if f"swelldem/{d}" in res["swelling"]}
    for key, r in res["swelling"].items():
        law, d = key.split("/")
        q = r["fn_p05_p95_N"]
        f = np.array(r["fn_N"])
        dev = float(np.max(np.abs(f - ref[d])) / np.max(np.abs(ref[d]))) if d in ref and law != "swelldem" else float("nan")
        srows.append({"law": law, "damage": d == "dmg", "eps_xx_1e-6": r["eps_xx"] * 1e6, "eps_yy_1e-6": r["eps_yy"] * 1e6,
                      **{f"fn_{i}_kN_{n}": q[n][k] / 1e3 for n in KIND_NAMES for k, i in enumerate(("p05", "p95"))},
                      **{f"broken_{n}": r["broken_end"][n] for n in KIND_NAMES}, "max_dFn_rel_to_swelldem": dev,
                      "steps": r["steps"], "wall_s": r["wall_s"], "status": r["status"]})
    with open(os.path.join(args.out, "swelling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(srows[0]))
        w.writeheader()
        w.writerows(srows)
    lines += ["", f"## Free swelling of the mortar (eps_inf {args.eps_inf:g} on mortar discs, aggregates inert; ISR kinetics 1 -> 3650 d, "
                  f"xi fraction {next(iter(res['swelling'].values()))['xi_fraction']:.6f})", "",
              "swelldem: its own swelling law (per-contact d_inf = g_i r_i + g_j r_j, ADR over log time, 10 steps a decade); "
              "stock laws: radii of the mortar discs grown by the same amount over 4000 Newton steps, then relaxed.", "",
              "| law | damage | eps_xx (1e-6) | eps_yy (1e-6) | Fn 5 % / 95 % MORTAR (kN) | ITZ (kN) | AGG (kN) | broken M/I/A | "
              "max dFn / max Fn against swelldem | steps | wall (s) |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in srows:
        lines.append(f"| {cc.LAW_TITLES[r['law']]} | {'on' if r['damage'] else 'off'} | {r['eps_xx_1e-6']:.1f} | {r['eps_yy_1e-6']:.1f} | "
                     + " | ".join(f"{r[f'fn_p05_kN_{n}']:.2f} / {r[f'fn_p95_kN_{n}']:.2f}" for n in KIND_NAMES)
                     + f" | {r['broken_MORTAR']}/{r['broken_ITZ']}/{r['broken_AGG']} | "
                     + ("-" if r["law"] == "swelldem" else f"{r['max_dFn_rel_to_swelldem']:.2g}") + f" | {r['steps']} | {r['wall_s']:.1f} |")
lines.append(f"Total wall time {time.time() - t_start:.0f} s.")
with open(os.path.join(args.out, "table.md"), "w") as f:
    f.write("\n".join(lines) + "\n")

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

styles = {"swelldem": ("k", "-"), "cohfrict": ("tab:orange", "--"), "jcfpm": ("tab:green", ":"), "cpm": ("tab:purple", "-.")}
fig, axes = plt.subplots(1, max(1, len(uniaxial)), figsize=(5.5 * max(1, len(uniaxial)), 4))
axes = np.atleast_1d(axes)
for ax, case in zip(axes, uniaxial):
    for law in cc.LAWS:
        r = res["runs"].get(f"{law}/{case}")
        if r:
            c, ls = styles[law]
            ax.plot(np.array(r["strain"]) * 1e6, np.array(r["stress_Pa"]) / 1e6, color=c, ls=ls, lw=1.3, label=cc.LAW_TITLES[law])
    ax.set(xlabel=f"{case} strain [1e-6]", ylabel=f"{case} stress [MPa]", title=f"uniaxial {case}")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(args.out, "stress_strain.png"), dpi=120)
plt.close(fig)

colors = {"MORTAR": "tab:blue", "ITZ": "tab:red", "AGG": "tab:green"}
maps = [(key.split("/")[0], key.split("/")[1], r["broken_contacts_end"], f"end strain {r['strain'][-1] * 1e6:.0f}e-6")
        for key, r in res["runs"].items()]
maps += [(key.split("/")[0], "swelling-dmg", r["broken_contacts_end"], f"free swelling, eps {r['eps_xx'] * 1e6:.0f} / {r['eps_yy'] * 1e6:.0f} e-6")
         for key, r in res.get("swelling", {}).items() if key.endswith("/dmg")]
for law, case, broken_end, subtitle in maps:
    fig, ax = plt.subplots(figsize=(5, 5 * assembly.height_m / assembly.width_m))
    for poly in assembly.polygons:
        q = np.asarray(poly) * 1e3
        ax.fill(q[:, 0], q[:, 1], color="0.85", lw=0.5, ec="0.5")
    broken = np.array(broken_end, dtype=int)
    for k, name in enumerate(KIND_NAMES):
        sel = broken[assembly.kind[broken] == k] if len(broken) else broken
        segs = [[(s[0], s[1]), (s[2], s[3])] for s in assembly.facet_segment_m[sel] * 1e3]
        if segs:
            ax.add_collection(LineCollection(segs, colors=colors[name], linewidths=1.5, label=f"{name} ({len(segs)})"))
    ax.set_xlim(0, assembly.width_m * 1e3)
    ax.set_ylim(0, assembly.height_m * 1e3)
    ax.set_aspect("equal")
    ax.set(xlabel="x [mm]", ylabel="y [mm]", title=f"{cc.LAW_TITLES[law]}, {case}\n{subtitle}")
    if len(broken):
        ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, f"crack_{law}_{case}.png"), dpi=110)
    plt.close(fig)
res["wall_s"] = time.time() - t_start
save()
log(f"wrote {args.out}/results.json, table.md, table.csv, stress_strain.png, crack_*.png")
