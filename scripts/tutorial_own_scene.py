# SPDX-License-Identifier: GPL-2.0-or-later
"""Tutorial: a swelling test of one's own, built from the library's pieces (docs/guide.md, section 4).

  scripts/yade-swelldem -j 1 -n -x scripts/tutorial_own_scene.py --out out/tutorial

A 20 x 20 mm concrete with 30 % aggregates, ISR swelling of the mortar only (the ITZ and the
aggregates do not swell), aging viscoelastic mortar and ITZ with per-kind tensile strengths,
the implicit solver at 5 steps a decade from 1 to 3650 days. Writes OUT/mesostructure.png,
OUT/history.csv (one row per physical step, units in the header) and OUT/history.png (strain
and broken contacts against time), and through swelldem.dem.standard_outputs the files of
scripts/swelling_test.py (results.json, curves.csv, tables, figures, crack maps, vtk/).
About 8 s on one core.
"""
# --- 0. Command line: only the output folder --------------------------------------------------
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))), "py"))
from swelldem import dem, meso, options, paper  # noqa: E402
from swelldem.measure import affine_strain  # noqa: E402
from yade import O  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--out", default="out/tutorial", help="output folder")
args = ap.parse_args(sys.argv[1:])
with options.refuse_bad("tutorial_own_scene.py"):
    options.output_folder("out", args.out)
os.makedirs(args.out, exist_ok=True)

# --- 1. Mesostructure (plain geometry, lengths in mm; the assembly is in metres) --------------
assembly = meso.generate(seed=1, width_mm=20, height_mm=20, aggregate_area_fraction=0.30)
meso.plot_mesostructure(assembly, os.path.join(args.out, "mesostructure.png"))
print(f"tutorial: {assembly.n_particles} discs, {assembly.n_contacts} contacts, {assembly.n_aggregates} aggregates")

# --- 2. Contact kinds: stiffness, creep, swelling, strength of each ---------------------------
# The swelling of a contact: d_inf = eps_inf x 2 R_mean (the paper's Table 3.2 rule), in metres.
d_inf = 1000e-6 * 2 * float(assembly.r.mean())
kinds = {
    # mortar: the paper's B3 q's of mortar, ISR kinetics, swells, f_t = 3.5 MPa
    "MORTAR": dem.contact_kind("MORTAR", behaviour="viscoelastic", b3="mortar", kinetics="isr",
                               swell_disp_inf=d_inf, damage=True, tensile_strength=3.5e6),
    # ITZ: the paper's ITZ q's, no swelling, the weakest kind (f_t = 1.5 MPa)
    "ITZ": dem.contact_kind("ITZ", behaviour="viscoelastic", b3="itz", damage=True, tensile_strength=1.5e6),
    # aggregates: linear elastic, 60 GPa, f_t = 6 MPa
    "AGG": dem.contact_kind("AGG", behaviour="elastic", young=paper.AGGREGATE_YOUNG, damage=True,
                            tensile_strength=6e6),
}

# --- 3. Solver: physical times in days, evenly spaced in log time -----------------------------
# "implicit" (exact equilibria; docs/performance.md 1b) or "adr" (the paper's method, tolerance 1e-4).
solver = dem.make_solver("implicit", tStart=1.0, tEnd=3650.0, stepsPerDecade=5)

# --- 4. The YADE scene: discs, materials, bonded contacts with their facet areas --------------
scene = dem.to_yade(assembly, kinds, solver)

# --- 5. Recording: a Python function the solver calls after every converged step -------------
reference = np.column_stack([assembly.x, assembly.y])
# discs with fewer than 2 contacts are loose in a free specimen and do not follow its strain
weights = np.where(assembly.coordination() >= 2, assembly.r ** 2, 0.0)
rows = []


def record():
    strain = affine_strain(reference, scene.positions(), weights=weights)
    row = {"time_days": solver.physTime, "strain_x": strain["eps_xx"], "strain_y": strain["eps_yy"],
           "iterations": int(solver.stepIterations[-1])}
    for name, k in paper.KIND_IDS.items():
        phys = [i.phys for i in O.interactions if i.isReal and i.phys.kindId == k]
        fn_kN = np.array([p.Fn for p in phys]) / 1e3
        row[f"fn_p95_kN_{name}"] = float(np.quantile(fn_kN, 0.95))
        row[f"broken_{name}"] = sum(p.broken for p in phys)
    rows.append(row)


solver.stepHook = record
# and the outputs of scripts/swelling_test.py: results.json, curves.csv, tables, figures, ParaView files
dem.standard_outputs(args.out, assembly, scene, solver, name="tutorial, mortar swelling", vtk_every=5)
dem.run_to_end(solver)

# --- 6. Results: a CSV with units in the header, and a plot ------------------------------------
csv_path = os.path.join(args.out, "history.csv")
units = {"time_days": "time [day]", "strain_x": "strain x [-]", "strain_y": "strain y [-]", "iterations": "solver iterations [-]"}
units.update({f"fn_p95_kN_{n}": f"Fn 95 % {n} [kN]" for n in paper.KIND_NAMES})
units.update({f"broken_{n}": f"broken {n} [-]" for n in paper.KIND_NAMES})
with open(csv_path, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow([units[k] for k in rows[0]])
    for row in rows:
        w.writerow([f"{v:.6g}" if isinstance(v, float) else v for v in row.values()])

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

t = [r["time_days"] for r in rows]
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
ax1.semilogx(t, [r["strain_x"] * 1e6 for r in rows], "o-", label="x")
ax1.semilogx(t, [r["strain_y"] * 1e6 for r in rows], "s-", label="y")
ax1.set_xlabel("time [day]")
ax1.set_ylabel("swelling strain [1e-6]")
ax1.legend()
for name in paper.KIND_NAMES:
    ax2.semilogx(t, [r[f"broken_{name}"] for r in rows], "o-", label=name)
ax2.set_xlabel("time [day]")
ax2.set_ylabel("broken contacts [-]")
ax2.legend()
fig.suptitle("own scene: 20 x 20 mm, ISR swelling of the mortar, viscoelastic, damage")
fig.tight_layout()
fig.savefig(os.path.join(args.out, "history.png"), dpi=100)
print(f"tutorial: {len(rows)} steps, final strain x {rows[-1]['strain_x'] * 1e6:.0f}e-6 y {rows[-1]['strain_y'] * 1e6:.0f}e-6; "
      f"{csv_path}, {os.path.join(args.out, 'history.png')}")
