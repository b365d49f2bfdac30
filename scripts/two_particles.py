# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's Table 3.1: two discs of radius 0.5 m, one contact, free swelling with
d_inf = 1000e-6 m; ISR to 3650 days or ASR to 50000 days. With --restrained both discs are held
and the relaxed compressive force history is compared with the physics core's own prediction.

  scripts/yade-swelldem -n -x scripts/two_particles.py --case isr|asr --steps-per-decade N --out DIR
writes DIR/results.json (case, steps_per_decade, times_days, strain, eps_final, adr_iterations, wall_s, ...)
and DIR/swelling.png."""
import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import options, paper  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--case", choices=tuple(paper.KINETICS), default="isr")
ap.add_argument("--steps-per-decade", type=float, default=10)
ap.add_argument("--out", default="out/two_particles")
ap.add_argument("--behaviour", choices=("elastic", "aging-elastic", "viscoelastic"), default=None,
                help="contact behaviour (default: elastic when free, viscoelastic when restrained)")
ap.add_argument("--restrained", action="store_true", help="hold both discs: relaxed compressive force history")
ap.add_argument("--tolerance", type=float, default=1e-6, help="ADR unbalanced-force ratio")
ap.add_argument("--t-start", type=float, default=0.01, help="age of the stress-free start [day]")

from yade import wrapper as W  # noqa: E402
import yade  # noqa: E402
from swelldem import dem  # noqa: E402

O = yade.Omega()
R, D_INF = 0.5, 1000e-6  # [m] the paper's Table 3.1 pair: d_inf = eps_inf x 2 R with eps_inf = 1000e-6
with options.refuse_bad("two_particles.py"):  # every option, then the plugin's constructors, before any work
    args = ap.parse_args(sys.argv[1:])
    behaviour = args.behaviour or ("viscoelastic" if args.restrained else "elastic")
    t_end = paper.KINETICS[args.case][2]
    options.number("steps_per_decade", args.steps_per_decade, lo=0)
    options.tolerance("tolerance", args.tolerance)
    options.number("t_start", args.t_start, lo=0, hi=t_end, unit="day", allowed=f"0 < t_start < {t_end:g} (the end of {args.case}) [day]")
    options.output_folder("out", args.out)
    kind = dem.contact_kind("MORTAR", behaviour=behaviour, young=30e9, b3="mortar", swell_disp_inf=D_INF, kinetics=args.case)
    solver = dem.make_solver("adr", tStart=args.t_start, tEnd=t_end, stepsPerDecade=args.steps_per_decade, tolerance=args.tolerance,
                             label="solver")
os.makedirs(args.out, exist_ok=True)
t0 = time.time()

# The pair touches (centre distance 2R): the collider finds the contact at the first iteration.
mat = W.ConcreteMat(young=30e9, poisson=0.2, density=2400, aggregateId=-1, label="mortar")
dem.build_scene([0.0, 2 * R], [0.0, 0.0], [R, R], [mat], W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(mortar=kind, itz=kind, agg=kind),
                W.Law2_ScGeom_SwellPhys_AgingSwelling(), solver, fixed=[0, 1] if args.restrained else [0], detection_factor=1.05)
history = {"times_days": [args.t_start], "strain": [0.0], "fn_N": [0.0]}


def record():
    i = O.interactions[0, 1]
    history["times_days"].append(solver.physTime)
    history["strain"].append((O.bodies[1].state.pos[0] - O.bodies[0].state.pos[0] - 2 * R) / (2 * R))
    history["fn_N"].append(i.phys.Fn)


solver.stepHook = record
dem.run_to_end(solver)
i = O.interactions[0, 1]
res = {"case": args.case, "steps_per_decade": args.steps_per_decade, "behaviour": behaviour, "restrained": args.restrained,
       "times_days": history["times_days"], "strain": history["strain"], "eps_final": history["strain"][-1],
       "fn_N": history["fn_N"], "adr_iterations": solver.totalIterations, "adr_iterations_per_step": solver.stepIterations,
       "n_steps": solver.nSteps, "tolerance": args.tolerance, "d_inf_m": D_INF, "radius_m": R,
       "paper_eps_final": 1000e-6, "contact_area_m2": i.phys.area, "contact_length_m": i.phys.length,
       "b3_q_per_Pa": [kind.q1, kind.q2, kind.q3, kind.q4], "kinetics_days": [kind.tauC, kind.tauL], "wall_s": time.time() - t0}
if args.restrained:
    core = kind.evaluateHistory(list(solver.times), [0.0] * len(solver.times), i.phys.area, i.phys.length, -1.0)
    res["fn_core_N"] = core
    res["max_rel_diff_vs_core"] = max(abs(a - b) / max(abs(b), 1e-300) for a, b in zip(history["fn_N"][1:], core[1:]))
with open(os.path.join(args.out, "results.json"), "w") as f:
    json.dump(res, f, indent=1)

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
fig, ax = plt.subplots(figsize=(6, 4))
if args.restrained:
    ax.semilogx(res["times_days"][1:], [f / 1e3 for f in res["fn_N"][1:]], "o-", ms=3, label="YADE + plugin")
    ax.semilogx(res["times_days"][1:], [f / 1e3 for f in res["fn_core_N"][1:]], "--", label="physics core alone")
    ax.set_ylabel("normal force Fn [kN] (tension > 0)")
else:
    ax.semilogx(res["times_days"][1:], [e * 1e6 for e in res["strain"][1:]], "o-", ms=3, label=f"N = {args.steps_per_decade:g}")
    ax.axhline(1000, color="k", lw=0.5)
    ax.set_ylabel("swelling strain [1e-6]")
ax.set_xlabel("time [day]")
ax.set_title(f"two particles, {args.case.upper()}, {behaviour}{', restrained' if args.restrained else ''}")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(args.out, "swelling.png"), dpi=120)
print(f"two_particles: {args.case} N={args.steps_per_decade:g} eps_final={res['eps_final'] * 1e6:.2f}e-6 (paper 1000e-6), "
      f"ADR iterations {res['adr_iterations']}, wall {res['wall_s']:.1f} s -> {args.out}")
