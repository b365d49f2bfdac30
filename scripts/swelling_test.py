# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's numerical swelling tests on a generated concrete specimen.

  scripts/yade-swelldem -n -x scripts/swelling_test.py --scenario isr|asr-fine|asr-coarse \
      --behaviour elastic|viscoelastic [--no-damage] [--size-mm W H] [--seed S] \
      [--steps-per-decade N] [--tolerance TOL] --out DIR

writes DIR/results.json, DIR/table.md, DIR/table.csv, DIR/*.png (swelling strain, unbalanced force,
force quantiles, crack map) and DIR/vtk/ (particles and contacts, through YADE's VTKExporter)."""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))), "py"))
from swelldem import scenario  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--scenario", choices=tuple(scenario.SCENARIOS), default="isr")
ap.add_argument("--behaviour", choices=scenario.BEHAVIOURS, default="viscoelastic")
ap.add_argument("--no-damage", action="store_true", help="contacts never break")
ap.add_argument("--size-mm", type=float, nargs=2, default=(30.0, 30.0), metavar=("W", "H"))
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--steps-per-decade", type=float, default=10)
ap.add_argument("--tolerance", type=float, default=1e-4, help="ADR unbalanced-force ratio")
ap.add_argument("--t-start", type=float, default=1.0, help="age of the stress-free start [day]")
ap.add_argument("--t-end", type=float, default=0.0, help="last time [day] (0: the paper's, 3650 ISR / 50000 ASR)")
ap.add_argument("--gel-fraction", type=float, default=0.1, help="asr-coarse: share of aggregate contacts that swell")
ap.add_argument("--kelvin-units-per-decade", type=float, default=1.0)
ap.add_argument("--parameters", choices=("paper-micro", "macro"), default="paper-micro",
                help="read the paper's Table 3.3 q's (and the aggregate modulus) as contact values, or as macroscopic ones scaled by the measured beta")
ap.add_argument("--eps-inf", type=float, default=1000e-6, help="ultimate free swelling strain of the swelling material")
ap.add_argument("--aggregate-young", type=float, default=scenario.AGGREGATE_YOUNG, help="contact modulus of aggregate contacts [Pa]")
ap.add_argument("--strength-scale", type=float, default=1.0, help="factor on the paper's tensile strengths")
ap.add_argument("--vtk-every", type=int, default=0, help="VTK every k physical steps (0: the last only)")
ap.add_argument("--out", default="out/swelling")
a = ap.parse_args(sys.argv[1:])
test = scenario.SwellingTest(scenario=a.scenario, behaviour=a.behaviour, damage=not a.no_damage, size_mm=tuple(a.size_mm),
                             seed=a.seed, steps_per_decade=a.steps_per_decade, tolerance=a.tolerance, t_start_days=a.t_start,
                             t_end_days=a.t_end, gel_fraction=a.gel_fraction, kelvin_units_per_decade=a.kelvin_units_per_decade, parameters=a.parameters, eps_inf=a.eps_inf,
                             aggregate_young=a.aggregate_young, strength_scale=a.strength_scale,
                             vtk_every=a.vtk_every, out=a.out)
try:
    test.validate()
except ValueError as e:
    sys.exit(f"swelling_test.py: {e}")
res = scenario.run(test)
print(f"swelling_test: {a.scenario} {a.behaviour} damage {'on' if test.damage else 'off'}: {res['n_particles']} particles, "
      f"strain x {res['swelling_strain_x'][-1] * 1e6:.0f}e-6 y {res['swelling_strain_y'][-1] * 1e6:.0f}e-6, "
      f"ADR iterations {res['adr_iterations']}, wall {res['wall_s']:.1f} s")
print(open(os.path.join(a.out, "table.md")).read())
print(f"results, tables and plots in {a.out}/ (swelling_strain.png, unbalanced.png, force_quantiles.png, crack_map.png, vtk/)")
