# SPDX-License-Identifier: GPL-2.0-or-later
"""One swelling test with damage on under either log-time solver and either break rule, built
from the scenarios' pieces (scenario.make_kinds, dem.make_solver, dem.to_yade), with nothing but
the run timed and the broken shares counted over the contacts bonded at the start:

    scripts/yade-swelldem -j 1 -n -x scripts/bench/bench_implicit_damage.py --scenario isr \\
        --behaviour elastic --size-mm 40 40 --seed 1 --solver implicit [--tolerance 0] \\
        [--break-rule all|one] [--steps-per-decade 10] [--parameters paper-micro] [--out DIR]

Prints one line `RESULT {json}`: status ('finished' or 'failed: <message>'), iterations, wall
time of the run [s] (set-up excluded), the final swelling strains, and the broken share [%] of the
contacts of each kind that were bonded at the start. docs/performance.md section 1b and
docs/contact-law-and-solver.md (break rule) quote its figures.
"""
import argparse
import ast
import json
import os
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "py"))
import numpy as np  # noqa: E402

from swelldem import dem, meso, options, paper, scenario  # noqa: E402
from swelldem.dem import recorder  # noqa: E402
from swelldem.measure import affine_strain  # noqa: E402


def main(argv):
    ap = argparse.ArgumentParser(prog="bench_implicit_damage.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenario", choices=list(paper.SCENARIOS), default="isr")
    ap.add_argument("--behaviour", choices=["elastic", "viscoelastic"], default="elastic")
    ap.add_argument("--size-mm", type=float, nargs=2, default=[20.0, 20.0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--solver", choices=["adr", "implicit"], default="implicit")
    ap.add_argument("--tolerance", type=float, default=0.0, help="0: the solver's own")
    ap.add_argument("--break-rule", choices=["all", "one"], default="all",
                    help="all overloaded contacts at once, or the most overloaded first (breakOneAtATime)")
    ap.add_argument("--steps-per-decade", type=float, default=10.0)
    ap.add_argument("--parameters", choices=["paper-micro", "macro"], default="paper-micro")
    ap.add_argument("--verbose", action="store_true", help="print the solver's progress line per step")
    ap.add_argument("--out", default="", help="also write the result as JSON into this folder (result.json)")
    ap.add_argument("--set", action="append", default=[], metavar="ATTR=VALUE",
                    help="a setting of the solver, e.g. lowRankChanges=0 (a Python literal; repeatable)")
    a = ap.parse_args(argv)
    with options.refuse_bad("bench_implicit_damage.py"):
        test = scenario.SwellingTest(scenario=a.scenario, behaviour=a.behaviour, damage=True, size_mm=list(a.size_mm),
                                     seed=a.seed, parameters=a.parameters, steps_per_decade=a.steps_per_decade,
                                     tolerance=a.tolerance, solver=a.solver,
                                     # the test's own folder is not written (only --out's result.json)
                                     out=a.out or tempfile.gettempdir())
        test.validate()
        kinds = scenario.make_kinds(test)
        settings = dict(tStart=test.t_start_days, tEnd=test.t_end, stepsPerDecade=test.steps_per_decade, verbose=a.verbose,
                        breakOneAtATime=a.break_rule == "one")
        if a.tolerance:
            settings["tolerance"] = a.tolerance
        for item in a.set:
            name, _, value = item.partition("=")
            try:
                settings[name] = ast.literal_eval(value)
            except (ValueError, SyntaxError):
                options.bad("set", item, "ATTR=VALUE with VALUE a Python literal")
        solver = dem.make_solver(a.solver, **settings)
    assembly = meso.generate(seed=test.seed, width_mm=test.size_mm[0], height_mm=test.size_mm[1])
    if test.parameters == "macro":
        scenario.scale_kinds(kinds, scenario.calibrate_modulus_factor(shear_ratio=test.shear_ratio)["beta"], test.kind_params)
    scenario.set_swelling(test, kinds, test.eps_inf * 2 * float(assembly.r.mean()))
    ys = dem.to_yade(assembly, kinds, solver)
    bonded = recorder.bonded_pairs()
    kind0, _, _, _ = recorder.contact_arrays(bonded)
    t0, status = time.time(), "finished"
    try:
        dem.run_to_end(solver)
    except Exception as e:  # noqa: BLE001 - the run's end is the measurement
        status = f"failed: {e}"
    wall = time.time() - t0
    # the measures of scripts/swelling_test.py (swelldem.dem.recorder): bonded contacts broken since
    # the start, over the bonded contacts of each kind; the skeleton's affine strain
    kind, _, broken, was_bonded = recorder.contact_arrays(bonded)
    pct = {n: round(100.0 * float((broken & was_bonded & (kind == k)).sum()) / max(int((kind0 == k).sum()), 1), 2)
           for k, n in enumerate(paper.KIND_NAMES)}
    strain = affine_strain(np.column_stack([assembly.x, assembly.y]), ys.positions(),
                           weights=np.where(assembly.coordination() >= 2, assembly.r ** 2, 0.0))
    result = {
        "scenario": a.scenario, "behaviour": a.behaviour, "size_mm": list(a.size_mm), "seed": a.seed, "solver": a.solver,
        "break_rule": a.break_rule, "status": status, "iterations": solver.totalIterations, "wall_s": round(wall, 2),
        "factorizations": getattr(solver, "factorizations", None), "settings": dict(item.split("=", 1) for item in a.set),
        "strain_x": float(strain["eps_xx"]), "strain_y": float(strain["eps_yy"]), "broken_pct": pct}
    print("RESULT " + json.dumps(result), flush=True)
    if a.out:
        os.makedirs(a.out, exist_ok=True)
        with open(os.path.join(a.out, "result.json"), "w") as f:
            json.dump(result, f, indent=1)


main(sys.argv[1:])
