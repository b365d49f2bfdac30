# SPDX-License-Identifier: GPL-2.0-or-later
"""One swelling test with damage on under either log-time solver and either break rule, built
as the scenarios build it (swelldem.scenario.build), with nothing but the run timed and the broken
shares counted over the contacts bonded at the start:

    scripts/yade-swelldem -j 1 -n -x scripts/bench/bench_implicit_damage.py --scenario isr \\
        --behaviour elastic --size-mm 40 40 --seed 1 --solver implicit [--tolerance TOL] \\
        [--break-rule all|one] [--steps-per-decade 10] [--parameters paper-micro] \\
        [--solver-param lowRankChanges=0 ...] [--out DIR]
    ... --dim 3 --size-mm 15 15 15 [--solver adr] [--aggregate-area-fraction F]   (a 3D box)

Prints one line `RESULT {json}`: status ('finished' or 'failed: <message>'), iterations, wall
time of the run [s] (set-up excluded), the final swelling strains, and the broken share [%] of the
contacts of each kind that were bonded at the start. docs/performance.md section 1b and
docs/contact-law-and-solver.md (break rule) quote its figures.
"""
import argparse
import json
import os
import resource
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "py"))

from swelldem import dem, options, paper, scenario  # noqa: E402
from swelldem.dem import recorder  # noqa: E402
from swelldem.measure import affine_strain  # noqa: E402


def main(argv):
    ap = argparse.ArgumentParser(prog="bench_implicit_damage.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenario", choices=list(paper.SCENARIOS), default="isr")
    ap.add_argument("--behaviour", choices=["elastic", "viscoelastic"], default="elastic")
    ap.add_argument("--size-mm", type=float, nargs="+", default=[20.0, 20.0], help="W H, or W H D with --dim 3")
    ap.add_argument("--dim", type=int, default=2, help="2: a section; 3: a box of spheres")
    ap.add_argument("--aggregate-area-fraction", type=float, default=-1.0, help="< 0: the generator's default")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--solver", choices=["adr", "implicit"], default="implicit")
    ap.add_argument("--tolerance", type=float, default=None, help="absent: the solver's own default")
    ap.add_argument("--break-rule", choices=["all", "one"], default="all",
                    help="all overloaded contacts at once, or the most overloaded first (breakOneAtATime)")
    ap.add_argument("--steps-per-decade", type=float, default=10.0)
    ap.add_argument("--parameters", choices=["paper-micro", "macro"], default="paper-micro")
    ap.add_argument("--verbose", action="store_true", help="print the solver's progress line per step")
    ap.add_argument("--out", default="", help="also write the result as JSON into this folder (result.json)")
    ap.add_argument("--solver-param", action="append", default=[], metavar="NAME=VALUE",
                    help="a setting of the solver, e.g. lowRankChanges=0 (a Python literal; repeatable), as swelling_test.py's")
    ap.add_argument("--steps", type=int, default=0,
                    help="stop after this many physical steps (the first is a whole intact step's solves); 0: the whole run")
    a = ap.parse_args(argv)
    with options.refuse_bad("bench_implicit_damage.py"):
        params = dict(scenario.parse_solver_param(text) for text in a.solver_param)
        params = {"verbose": a.verbose, "breakOneAtATime": a.break_rule == "one", **params}
        test = scenario.SwellingTest(scenario=a.scenario, behaviour=a.behaviour, damage=True, size_mm=tuple(a.size_mm), dim=a.dim,
                                     aggregate_area_fraction=a.aggregate_area_fraction,
                                     seed=a.seed, parameters=a.parameters, steps_per_decade=a.steps_per_decade,
                                     tolerance=a.tolerance, solver=a.solver, solver_params=params,
                                     # the test's own folder is not written (only --out's result.json)
                                     out=a.out or tempfile.gettempdir())
        t_build = time.time()
        prepared = scenario.prepare(test)
    built = scenario.build(test, prepared)
    solver, ys, assembly = built.solver, built.scene, built.assembly
    bonded = recorder.bonded_pairs()
    kind0, _, _, _ = recorder.contact_arrays(bonded)
    t0, status = time.time(), "finished"
    try:
        if a.steps > 0:
            # iteration by iteration: a 3D step's iteration takes seconds, the call's own cost 10 ms
            while not solver.finished and solver.step <= a.steps:
                dem.run_chunk_quietly(solver, 1)
            status = f"stopped after step {a.steps}" if not solver.finished else status
        else:
            dem.run_to_end(solver)
    except Exception as e:  # noqa: BLE001 - the run's end is the measurement
        status = f"failed: {e}"
    wall = time.time() - t0
    # the measures of scripts/swelling_test.py (swelldem.dem.recorder): bonded contacts broken since
    # the start, over the bonded contacts of each kind; the skeleton's affine strain
    kind, _, broken, was_bonded = recorder.contact_arrays(bonded)
    pct = {n: round(100.0 * float((broken & was_bonded & (kind == k)).sum()) / max(int((kind0 == k).sum()), 1), 2)
           for k, n in enumerate(paper.KIND_NAMES)}
    strain = affine_strain(recorder.reference_positions(assembly), ys.positions(), weights=recorder.skeleton_weights(assembly))
    result = {
        "scenario": a.scenario, "behaviour": a.behaviour, "size_mm": list(a.size_mm), "seed": a.seed, "solver": a.solver,
        "break_rule": a.break_rule, "status": status, "iterations": solver.totalIterations, "wall_s": round(wall, 2),
        "factorizations": getattr(solver, "factorizations", None), "factor_wall_s": getattr(solver, "factorSeconds", None),
        "factor_nonzeros": getattr(solver, "factorNonZeros", None), "build_s": round(t0 - t_build, 2),
        "linear_solver": getattr(solver, "linearSolverUsed", None), "krylov_solves": getattr(solver, "krylovSolves", None),
        "krylov_iterations": getattr(solver, "krylovIterations", None), "krylov_failures": getattr(solver, "krylovFailures", None), "settings": dict(item.split("=", 1) for item in a.solver_param),
        "strain_x": float(strain["eps_xx"]), "strain_y": float(strain["eps_yy"]), "broken_pct": pct,
        "n_particles": int(len(assembly.x)), "n_contacts": int(len(ys.contacts)),
        "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1)}
    if a.dim == 3:
        result.update(dim=3, strain_z=float(strain["eps_zz"]))
    print("RESULT " + json.dumps(result), flush=True)
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        with open(os.path.join(a.out, "result.json"), "w") as f:
            json.dump(result, f, indent=1)


main(sys.argv[1:])
