# SPDX-License-Identifier: GPL-2.0-or-later
"""Uniaxial compressive strength of the 3D prism of scripts/loaded_expansion.py: the same
specimen without swelling (eps_inf 0), between rigid lubricated z platens, shortened step by step
(displacement control) at one age until past its peak.

    scripts/yade-swelldem -j 1 -n -x scripts/prism_strength.py --strength-scale 1 --out out/fc-s1
        [--size-mm 12 12 24] [--seed 1] [--aggregate-area-fraction 0.2] [--age 28]
        [--strain-step 50e-6] [--max-strain 4e-3] [--drop 0.85] [--max-iterations 30000] [--step-iterations 40000]

The specimen is scripts/loaded_expansion.py's (ASR-fine viscoelastic prism with damage, the
paper's contact values with every tensile strength times --strength-scale), built by
swelldem.scenario.build with --boundary-z fixed: the platens of swelldem.dem.platens (steel,
lubricated, bonded to the facing spheres), the x and y sides free. After the first converged
step the high z platen moves by --strain-step x the platens' distance towards the low one before
each further step; the ADR brings each step to equilibrium (contacts break between rounds, as in
a swelling run). The physical times are spread evenly over residual.TEST_SPAN x age after the age
(0.0028 day at 28 days: a short-term test, as swelldem.residual's; the contacts' creep over it is
that of their B3 compliance, not zero). Stress = the
platens' mean reaction over the nominal face W x H [Pa] (compression positive), strain = the
platens' shortening over their initial distance. The test ends when the stress has fallen below
--drop x its peak, at --max-strain, or when a step finds no equilibrium within --max-iterations
(since its last breaks) or --step-iterations (in all): the prism has failed, its broken contacts
slide or break round after round under the imposed shortening;
in the last case, and whenever the peak is the last converged step, the peak is a lower bound of
the strength ('peak_lower_bound'). Writes DIR/strength.json (settings, curve, broken contacts per
kind, iterations per step, peak, modulus, status, wall time) and DIR/strength.csv. Bad values
stop before any work with 'prism_strength.py: swelldem: <option> = <value> is out of range;
allowed: <range>' and exit status 2.
"""
import argparse
import csv
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "py"))
from swelldem import options, paper, residual, scenario  # noqa: E402

PROG = "prism_strength.py"
ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--strength-scale", type=float, default=1.0, help="factor on the paper's Table 3.5 tensile strengths, > 0 [-]")
ap.add_argument("--size-mm", type=float, nargs=3, default=(12.0, 12.0, 24.0), metavar=("W", "H", "D"),
                help="prism size; the load acts along D (z) [mm]")
ap.add_argument("--seed", type=int, default=1, help="mesostructure seed")
ap.add_argument("--aggregate-area-fraction", type=float, default=0.2, help="aggregate volume fraction [-]")
ap.add_argument("--age", type=float, default=28.0, help="age at the test, > 0 [day]")
ap.add_argument("--strain-step", type=float, default=50e-6, help="platen shortening per step over the platens' distance, (0, 1e-3] [-]")
ap.add_argument("--max-strain", type=float, default=4e-3, help="the test ends at this strain, (0, 0.05] [-]")
ap.add_argument("--drop", type=float, default=0.85, help="the test ends when the stress falls below this fraction of the peak, (0, 1) [-]")
ap.add_argument("--max-iterations", type=int, default=30000,
                help="ADR iterations a step may take (since its last breaks) before it counts as without equilibrium, >= 100")
ap.add_argument("--step-iterations", type=int, default=40000,
                help="ADR iterations a step may take in all (its breaking rounds included) before the test ends as without "
                     "equilibrium, >= 100: past the peak contacts can break round after round, each round resetting "
                     "--max-iterations")
ap.add_argument("--out", required=True, help="output folder")
args = ap.parse_args(sys.argv[1:])

with options.refuse_bad(PROG):
    options.number("strength_scale", args.strength_scale, lo=0, unit="-")
    options.number("age", args.age, lo=0, unit="day")
    options.number("strain_step", args.strain_step, lo=0, hi=1e-3, hi_incl=True, unit="-")
    options.number("max_strain", args.max_strain, lo=0, hi=0.05, hi_incl=True, unit="-")
    options.number("drop", args.drop, lo=0, hi=1, unit="-")
    options.integer("max_iterations", args.max_iterations, lo=100)
    options.integer("step_iterations", args.step_iterations, lo=100)
    if args.max_strain < args.strain_step:
        options.bad("max_strain", args.max_strain, f"strain_step = {args.strain_step:g} <= max_strain <= 0.05 [-]")
    options.output_folder("out", args.out)
    max_steps = int(np.ceil(args.max_strain / args.strain_step)) + 1
    span = residual.TEST_SPAN * args.age
    extra = (args.age + span * np.arange(1, max_steps + 3) / (max_steps + 3)).tolist()
    test = scenario.SwellingTest(dim=3, scenario="asr-fine", behaviour="viscoelastic", damage=True, size_mm=tuple(args.size_mm),
                                 seed=args.seed, solver="adr", aggregate_area_fraction=args.aggregate_area_fraction,
                                 strength_scale=args.strength_scale, eps_inf=0.0, boundary_z="fixed", t_start_days=args.age,
                                 t_end_days=args.age + span, steps_per_decade=1e-3,
                                 solver_params={"maxIterations": args.max_iterations}, out=args.out)
    prepared = scenario.prepare(test, extra)

t0 = time.time()
built = scenario.build(test, prepared)
from swelldem.plugin import require  # noqa: E402

yade, _ = require(PROG)
O = yade.Omega()
solver, platens = built.solver, built.platens
lo_id, hi_id = platens.walls["z"]
depth0 = float(O.bodies[hi_id].state.pos[2] - O.bodies[lo_id].state.pos[2])
face = platens.area["z"]
kind_names = {int(k.kindId): name for name, k in built.kinds.items()}


class Loader:
    """The solver's stepHook: records (strain, stress, broken per kind) after each converged step,
    then moves the high platen by the next increment, or ends the test."""

    def __init__(self):
        self.strain, self.stress, self.broken, self.iterations = [], [], [], []
        self.done, self.status, self.it0 = False, "running", 0

    def __call__(self):
        eps = -platens.displacement("z") / depth0
        sig = -platens.stress("z")
        counts = {n: 0 for n in kind_names.values()}
        for I in O.interactions:
            if I.isReal and getattr(I.phys, "broken", False) and int(I.phys.kind.kindId) in kind_names:
                counts[kind_names[int(I.phys.kind.kindId)]] += 1
        it = int(solver.totalIterations)
        self.strain.append(eps)
        self.stress.append(sig)
        self.broken.append(counts)
        self.iterations.append(it - self.it0)
        self.it0 = it
        print(f"{PROG}: strain {eps * 1e6:8.1f}e-6  stress {sig / 1e6:7.3f} MPa  broken {counts}  iterations {self.iterations[-1]}",
              flush=True)
        peak = max(self.stress)
        if not np.isfinite(sig):
            return self.finish("diverged")
        if peak > 0 and sig < args.drop * peak:
            return self.finish("past_peak")
        if eps >= args.max_strain - 1e-12:
            return self.finish("max_strain")
        if len(self.strain) >= max_steps + 1:
            return self.finish("max_steps")
        b = O.bodies[hi_id]
        b.state.pos = b.state.pos - yade.Vector3(0, 0, args.strain_step * depth0)

    def finish(self, status):
        self.done, self.status = True, status
        O.stopAtIter = O.iter + 1


loader = Loader()
solver.stepHook = loader
residual.drive_test(solver, loader, step_iterations=args.step_iterations)

s = np.array(loader.stress)
e = np.array(loader.strain)
k = int(np.argmax(s))
out = {"settings": vars(args), "n_particles": int(len(built.assembly.x)), "n_contacts_by_kind": {
    n: int((built.assembly.kind == kid).sum()) for kid, n in enumerate(paper.KIND_NAMES)},
    "tensile_strength_Pa": {n: float(kk.tensileStrength) for n, kk in built.kinds.items()},
    "face_m2": face, "platen_distance_m": depth0, "strain": e.tolist(), "stress_Pa": s.tolist(), "broken": loader.broken,
    "iterations_per_step": loader.iterations, "status": loader.status, "peak_Pa": float(s[k]), "strain_at_peak": float(e[k]),
    "peak_lower_bound": residual.peak_is_lower_bound(s) or loader.status == "no_equilibrium" and k == len(s) - 1,
    "modulus_Pa": None,  # below: the fit needs two steps within its window
    "iterations": int(solver.totalIterations), "wall_s": time.time() - t0}
modulus = residual.modulus_fit(e, s, float(s[k])) if k >= 2 else float("nan")
out["modulus_Pa"] = float(modulus) if np.isfinite(modulus) else None
os.makedirs(args.out, exist_ok=True)
with open(os.path.join(args.out, "strength.json"), "w") as f:
    json.dump(out, f, indent=1)
with open(os.path.join(args.out, "strength.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["strain", "stress_Pa"] + [f"broken_{n}" for n in kind_names.values()] + ["iterations"])
    for i in range(len(e)):
        w.writerow([f"{e[i]:.6g}", f"{s[i]:.6g}"] + [loader.broken[i][n] for n in kind_names.values()] + [loader.iterations[i]])
print(f"{PROG}: fc {s[k] / 1e6:.2f} MPa{' (a lower bound)' if out['peak_lower_bound'] else ''} at strain {e[k] * 1e6:.0f}e-6, "
      f"E {out['modulus_Pa'] / 1e9 if out['modulus_Pa'] else float('nan'):.2f} GPa, status {loader.status}, "
      f"{out['iterations']} iterations, {out['wall_s']:.0f} s; {args.out}/strength.json", flush=True)
