# SPDX-License-Identifier: GPL-2.0-or-later
"""How many contacts a run without damage overloads: the share per kind of the contacts whose
tension exceeds their strength f_t A (Table 3.5's f_t, the contact's facet area) at the end of
some physical step. Set beside the broken share of the same run with damage, it says whether
cracking spreads the damage (more break than were overloaded: a cascade) or shields the rest
(fewer break: the broken contacts relieve their neighbours). docs/scenarios.md, "Elastic runs
with damage", uses it for the paper's elastic rows.

  scripts/yade-swelldem -j 1 -n -x scripts/overload_without_damage.py --scenario isr --size-mm 40 40 \\
      --seeds 1 2 3 --out DIR [--behaviour elastic]

Each seed is a swelling test without damage (swelldem.scenario, the implicit solver, 10 steps a
decade) in DIR/<scenario>-<behaviour>-s<seed>/; DIR/overload-<scenario>-<behaviour>.json and .md
hold the shares [%] per seed and their mean."""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "py"))
from swelldem import dem, options, paper, scenario  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--scenario", choices=tuple(paper.SCENARIOS), default="isr")
ap.add_argument("--behaviour", choices=("elastic", "viscoelastic"), default="elastic")
ap.add_argument("--size-mm", type=float, nargs=2, default=(40.0, 40.0), metavar=("W", "H"), help="specimen size [mm]")
ap.add_argument("--seeds", type=int, nargs="+", default=[1], help="mesostructure seeds [-]")
ap.add_argument("--out", required=True, help="output folder")
a = ap.parse_args(sys.argv[1:])
tests = [scenario.SwellingTest(scenario=a.scenario, behaviour=a.behaviour, damage=False, size_mm=tuple(a.size_mm), seed=s,
                               out=os.path.join(a.out, f"{a.scenario}-{a.behaviour}-s{s}")) for s in a.seeds]
try:
    for t in tests:
        t.validate()  # every seed's settings refused or accepted before the first run
except options.OptionError as e:
    sys.exit(f"overload_without_damage.py: {e}")

ft = np.array([paper.TENSILE_STRENGTH[n] for n in paper.KIND_NAMES])
shares = {}
for t in tests:
    b = scenario.build(t)
    pairs = [(int(i), int(j)) for i, j in b.scene.contacts]
    kind = np.asarray(b.assembly.kind)
    worst = np.full(len(pairs), -np.inf)  # the largest Fn / (f_t A) at a step's end

    def after_step():
        for c, (i, j) in enumerate(pairs):
            p = O.interactions[i, j].phys
            worst[c] = max(worst[c], p.Fn / (ft[kind[c]] * p.area))

    b.solver.stepHook = after_step
    dem.run_to_end(b.solver)
    shares[t.seed] = {n: float(100.0 * np.mean(worst[kind == k] >= 1.0)) for k, n in enumerate(paper.KIND_NAMES)}
    print(f"overload_without_damage: seed {t.seed}: " + ", ".join(f"{n} {v:.1f} %" for n, v in shares[t.seed].items()), flush=True)

mean = {n: float(np.mean([v[n] for v in shares.values()])) for n in paper.KIND_NAMES}
os.makedirs(a.out, exist_ok=True)
stem = os.path.join(a.out, f"overload-{a.scenario}-{a.behaviour}")
with open(stem + ".json", "w") as f:
    json.dump({"scenario": a.scenario, "behaviour": a.behaviour, "size_mm": list(a.size_mm), "per_seed_pct": shares,
               "mean_pct": mean}, f, indent=1)
lines = [f"# Contacts overloaded without damage: {a.scenario}, {a.behaviour}, {a.size_mm[0]:g} x {a.size_mm[1]:g} mm", "",
         "Share [%] of each kind's contacts whose tension exceeded f_t A at the end of some physical step.", "",
         "| seed | " + " | ".join(paper.KIND_NAMES) + " |", "|---|" + "---|" * len(paper.KIND_NAMES)]
lines += [f"| {s} | " + " | ".join(f"{v[n]:.1f}" for n in paper.KIND_NAMES) + " |" for s, v in shares.items()]
lines.append("| mean | " + " | ".join(f"{mean[n]:.1f}" for n in paper.KIND_NAMES) + " |")
with open(stem + ".md", "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"overload_without_damage: {stem}.md")
