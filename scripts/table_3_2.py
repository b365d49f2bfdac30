# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's Table 3.2: free swelling of a random mortar assembly (Rmax = 0.48 mm,
Rmin/Rmax = 2/3), every contact elastic and swelling with d_inf = eps_inf x 2 R_mean
(eps_inf = 1000e-6, R_mean the assembly's mean radius); ISR kinetics to 3650 days or ASR to
50000 days. The paper finds 1061e-6 at the end of both. Nothing is fixed: the swelling loads are
self-equilibrated, the solver starts from rest, and the rigid motions that round-off may leave
are removed by the strain measure (least-squares affine fit of the displacements of the particles
with at least 2 contacts; the few discs that the packing leaves held by the sides only are loose in a
free specimen and are left out).

  scripts/yade-swelldem -n -x scripts/table_3_2.py --size-mm 20 20 --seed 1 --out DIR [--case asr]
  scripts/yade-swelldem -n -x scripts/table_3_2.py --dim 3 --size-mm 12 12 12 --seed 1 --out DIR   (a box of spheres:
      the same rule's strain in 3D, the skeleton being the spheres with at least 3 contacts; eps_final is the
      mean of x, y and z, and the strain between the sides is not measured)
--d-inf-rule contact-length gives every contact d_inf = eps_inf x L instead (a compatible expansion:
the strain must then be eps_inf exactly, with no force left; a check of the chain scene-solver-measure).
Writes DIR/displacements.npz (reference and final centres, radii, contacts, final Fn), DIR/results.json (case, n_particles, r_mean_m, d_inf_m, eps_final_x/_y, eps_final,
paper_eps_final, times_days, strain curves, adr_iterations, wall_s, ...) and DIR/strain.png."""
import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import options, paper  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--size-mm", type=float, nargs="+", default=(20.0, 20.0), metavar="W H [D]", help="specimen size [mm] (W H D with --dim 3)")
ap.add_argument("--dim", type=int, default=2, choices=(2, 3), help="2: a section of discs; 3: a box of spheres")
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--case", choices=tuple(paper.KINETICS), default="isr")
ap.add_argument("--steps-per-decade", type=float, default=10)
ap.add_argument("--tolerance", type=float, default=1e-5, help="ADR unbalanced-force ratio")
ap.add_argument("--young", type=float, default=30e9, help="contact modulus E_c [Pa] (the free swelling strain does not depend on it)")
ap.add_argument("--eps-inf", type=float, default=paper.EPS_INF, help="target ultimate free swelling strain [-]")
ap.add_argument("--t-start", type=float, default=0.01, help="age of the stress-free start [day]")
ap.add_argument("--d-inf-rule", choices=("mean-radius", "contact-length"), default="mean-radius",
                help="mean-radius: the paper's d_inf = eps_inf x 2 R_mean on every contact; contact-length: "
                     "d_inf = eps_inf x L per contact (L its initial centre distance), a compatible expansion, as a check")
ap.add_argument("--out", default="out/table_3_2")

import numpy as np  # noqa: E402
import yade  # noqa: E402

from swelldem import dem, measure, meso  # noqa: E402

with options.refuse_bad("table_3_2.py"):  # every option, before any work; exit status 2 as argparse's
    args = ap.parse_args(sys.argv[1:])
    options.numbers("size_mm", args.size_mm, count=args.dim, lo=4, lo_incl=True,
                    allowed=f"{'two' if args.dim == 2 else 'three'} finite lengths >= 4 [mm] (a few particles)")
    options.integer("seed", args.seed, lo=0)
    options.number("steps_per_decade", args.steps_per_decade, lo=0)
    options.tolerance("tolerance", args.tolerance)
    options.number("young", args.young, lo=0, unit="Pa")
    options.number("eps_inf", args.eps_inf, lo=0)
    tau_c, tau_l, t_end = paper.KINETICS[args.case]
    options.number("t_start", args.t_start, lo=0, hi=t_end, unit="day", allowed=f"0 < t_start < {t_end:g} (the end of {args.case}) [day]")
    options.output_folder("out", args.out)
    # The plugin's objects first: their constructors check the rest (tStart < tEnd, ...). The
    # kind's d_inf depends on the assembly and is set once it exists.
    kind = dem.contact_kind("MORTAR", behaviour="elastic", young=args.young, b3="mortar", kinetics=args.case, swelling=True)
    solver = dem.make_solver("adr", tStart=args.t_start, tEnd=t_end, stepsPerDecade=args.steps_per_decade, tolerance=args.tolerance,
                             label="solver")

O = yade.Omega()
PAPER_EPS_FINAL = paper.TABLE_3_2_EPS_FINAL
t0 = time.time()
os.makedirs(args.out, exist_ok=True)

box = dict(dim=3, depth_mm=args.size_mm[2]) if args.dim == 3 else {}
a = meso.generate(seed=args.seed, width_mm=args.size_mm[0], height_mm=args.size_mm[1], aggregate_area_fraction=0.0, **box)
r_mean = float(a.r.mean())
d_inf = args.eps_inf * 2 * r_mean
kind.swellDispInf = d_inf
ys = dem.to_yade(a, {"MORTAR": kind}, solver)
if args.d_inf_rule == "contact-length":
    dem.set_contact_swelling(ys, np.arange(a.n_contacts), args.eps_inf * a.distance_m)
ref = np.column_stack([a.x, a.y] + ([a.z] if args.dim == 3 else []))
# The strain is measured on the load-bearing skeleton: particles with at least as many contacts as
# dimensions. The packing leaves a few particles held only by the specimen sides; in a free
# specimen they do not follow the expansion (no contact) or pivot freely (fewer).
coordination = a.coordination()
skeleton = coordination >= args.dim
hist = {"times_days": [args.t_start], "eps_x": [0.0], "eps_y": [0.0], "eps_xy": [0.0], "eps_side_x": [0.0], "eps_side_y": [0.0],
        "eps_robust_x": [0.0], "eps_robust_y": [0.0], "rotation_rad": [0.0], "residual_rms_m": [0.0]}
if args.dim == 3:
    hist.update(eps_z=[0.0], eps_robust_z=[0.0])
    del hist["eps_side_x"], hist["eps_side_y"], hist["rotation_rad"]


def table_3_2_record():
    cur = ys.positions()[skeleton]
    f = measure.affine_strain(ref[skeleton], cur)
    rb = measure.affine_strain(ref[skeleton], cur, robust=True)
    hist["times_days"].append(solver.physTime)
    for key, v in (("eps_x", f["eps_xx"]), ("eps_y", f["eps_yy"]), ("eps_xy", f["eps_xy"]), ("eps_robust_x", rb["eps_xx"]),
                   ("eps_robust_y", rb["eps_yy"]), ("residual_rms_m", f["residual_rms"])):
        hist[key].append(v)
    if args.dim == 3:
        hist["eps_z"].append(f["eps_zz"])
        hist["eps_robust_z"].append(rb["eps_zz"])
        return
    sd = measure.side_strain(ref[skeleton], cur, a.r[skeleton], band=a.r.max())
    for key, v in (("eps_side_x", sd["eps_x"]), ("eps_side_y", sd["eps_y"]), ("rotation_rad", f["rotation"])):
        hist[key].append(v)


solver.stepHook = table_3_2_record
dem.run_to_end(solver)

# Contact forces at the end: free swelling of a disordered network leaves self-stress, because
# one d_inf on contacts of different lengths L is not a compatible (affine) strain field.
fn = np.array([ys.interaction(c).phys.Fn for c in range(a.n_contacts)])
L, A = a.distance_m, a.facet_area_m2
eps_x, eps_y = hist["eps_x"][-1], hist["eps_y"][-1]
axes_eps = [eps_x, eps_y] + ([hist["eps_z"][-1]] if args.dim == 3 else [])
eps_final = float(np.mean(axes_eps))
robust = [hist[f"eps_robust_{k}"][-1] for k in "xyz"[:args.dim]]
side = None if args.dim == 3 else 0.5 * (hist["eps_side_x"][-1] + hist["eps_side_y"][-1])
xi_end, xi_start = float(paper.larive_xi(t_end, args.case)), float(paper.larive_xi(args.t_start, args.case))
res = {
    "case": args.case, "d_inf_rule": args.d_inf_rule, "size_mm": list(args.size_mm), "seed": args.seed, "n_particles": a.n_particles, "n_contacts": a.n_contacts,
    "n_new_contacts": sum(1 for i in O.interactions if i.isReal) - a.n_contacts,
    "mean_coordination": a.mean_coordination, "n_measured": int(skeleton.sum()),
    "n_excluded_by_contacts": {"0": int((coordination == 0).sum()), "1": int((coordination == 1).sum())}, "r_mean_m": r_mean, "r_min_m": float(a.r.min()), "r_max_m": float(a.r.max()),
    "eps_inf": args.eps_inf, "d_inf_m": d_inf if args.d_inf_rule == "mean-radius" else None, "young_Pa": args.young, "tau_c_days": tau_c, "tau_l_days": tau_l,
    "t_start_days": args.t_start, "t_end_days": t_end, "steps_per_decade": args.steps_per_decade, "tolerance": args.tolerance,
    "xi_end_minus_xi_start": float(xi_end - xi_start),
    "dim": args.dim, "eps_final_x": eps_x, "eps_final_y": eps_y, "eps_final_z": hist["eps_z"][-1] if args.dim == 3 else None,
    "eps_final": eps_final, "eps_final_xy": hist["eps_xy"][-1],
    "eps_final_side_x": None if side is None else hist["eps_side_x"][-1], "eps_final_side_y": None if side is None else hist["eps_side_y"][-1],
    "eps_final_side": side, "eps_final_robust": float(np.mean(robust)),
    "eps_final_over_eps_inf": eps_final / args.eps_inf,
    # the paper's figure is a section's: a box is not set beside it
    "paper_eps_final": PAPER_EPS_FINAL if args.dim == 2 else None, "paper_r_mean_m": paper.TABLE_3_2_R_MEAN,
    # Affine estimate: uniform isotropic strain e with no shear; equilibrium of the whole network
    # in the trace gives sum kn (e L - d) L = 0, kn = E A / L, hence e = d_inf / (A-weighted mean L).
    "eps_affine_estimate": float(d_inf * A.sum() / (A * L).sum()) if args.d_inf_rule == "mean-radius" else args.eps_inf,
    "contact_length_mean_m": float(L.mean()), "contact_length_area_weighted_mean_m": float((A * L).sum() / A.sum()),
    "final_fn_quantiles_N": {"p5": float(np.quantile(fn, 0.05)), "p50": float(np.quantile(fn, 0.5)), "p95": float(np.quantile(fn, 0.95))},
    # mean |Fn| left at the end, over the mean force a fully restrained contact would carry
    "final_fn_over_free_swelling_force": float(np.abs(fn).mean() / np.mean(args.young * A / L * args.eps_inf * 2 * r_mean)),
    **hist,
    "adr_iterations": solver.totalIterations, "adr_iterations_per_step": list(solver.stepIterations), "n_steps": solver.nSteps,
    "setup": ys.counts, "wall_s": time.time() - t0,
}
np.savez_compressed(os.path.join(args.out, "displacements.npz"), ref_xy=ref, cur_xy=ys.positions(), r=a.r,
                    contacts=a.contacts, fn_N=fn)
with open(os.path.join(args.out, "results.json"), "w") as f:
    json.dump(res, f, indent=1)

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
fig, ax = plt.subplots(figsize=(6.4, 4.2))
t = res["times_days"][1:]
ax.semilogx(t, np.array(hist["eps_x"][1:]) * 1e6, "o-", ms=3, label="x (affine fit)")
ax.semilogx(t, np.array(hist["eps_y"][1:]) * 1e6, "s-", ms=3, mfc="none", label="y (affine fit)")
if args.dim == 3:
    ax.semilogx(t, np.array(hist["eps_z"][1:]) * 1e6, "^-", ms=3, mfc="none", label="z (affine fit)")
else:
    ax.semilogx(t, 0.5 * (np.array(hist["eps_side_x"][1:]) + np.array(hist["eps_side_y"][1:])) * 1e6, ":", label="mean, between sides")
tt = np.array(t)
xi = paper.larive_xi(tt, args.case)
ax.semilogx(tt, args.eps_inf * xi * 1e6, "k--", lw=0.8, label="eps_inf xi(t) (micro-macro rule)")
if args.dim == 2:  # the paper's figure is a section's
    ax.axhline(PAPER_EPS_FINAL * 1e6, color="r", lw=0.8, label="paper, Table 3.2: 1061")
ax.set_xlabel("time [day]")
ax.set_ylabel("free swelling strain [1e-6]")
what = "spheres" if args.dim == 3 else "discs"
ax.set_title(f"Table 3.2, {args.case.upper()}{'' if args.d_inf_rule == 'mean-radius' else ', d_inf = eps_inf L'}: {a.n_particles} {what}, "
             f"{' x '.join(f'{v:g}' for v in args.size_mm)} mm, seed {args.seed}")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(args.out, "strain.png"), dpi=120)
z_text = f" z={hist['eps_z'][-1] * 1e6:.1f}e-6" if args.dim == 3 else ""
print(f"table_3_2: {args.case} {a.n_particles} {what} R_mean={r_mean * 1e3:.4f} mm d_inf rule {args.d_inf_rule} "
      f"(2 eps_inf R_mean = {d_inf * 1e6:.4f}e-6 m): "
      f"eps_final x={eps_x * 1e6:.1f}e-6 y={eps_y * 1e6:.1f}e-6{z_text} mean={res['eps_final'] * 1e6:.1f}e-6 "
      f"(affine estimate {res['eps_affine_estimate'] * 1e6:.1f}e-6{', paper 1061e-6' if args.dim == 2 else ''}), "
      f"ADR iterations {res['adr_iterations']}, wall {res['wall_s']:.1f} s -> {args.out}")
