#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Cost of a 3D box's swelling test under both solvers against the cube's side: run wall time,
peak memory, iterations, the implicit solver's factorizations, their time and the factor's
entries (fill-in), spheres and contacts, strains and broken shares, and the implicit run's wall
time over the ADR's at each size (both measured in this call).

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_3d.py [--sizes-mm 12 15 20]
        [--solvers adr implicit] [--aggregate-area-fraction 0.2] [--steps-per-decade 2] [--seed 1]
        [--json out/bench_3d.json]

Each size and solver is one run of scripts/bench/bench_implicit_damage.py (--dim 3, ISR
viscoelastic with damage) in its own process on one thread, which reports its own peak resident
size. The power law of each solver's wall time against the spheres is fitted and a 100 mm cube's
projected from it (the spheres scale with the volume); for the implicit solver the factor's
entries are fitted too (its memory: 8 bytes an entry plus CHOLMOD's indices). The aggregate
fraction is below the default 35 % so that cubes under 25 mm place their grains
(docs/mesostructure.md).
"""
import argparse
import os

import _common as C  # noqa: E402  (puts py/ on the path)

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bench_implicit_damage.py")


def one(size, solver, fraction, spd, seed):
    cmd = [C.LAUNCHER, "-n", "-j", "1", "-x", SCRIPT, "--dim", "3", "--size-mm", str(size), str(size), str(size),
           "--solver", solver, "--scenario", "isr", "--behaviour", "viscoelastic", "--seed", str(seed),
           "--steps-per-decade", str(spd), "--aggregate-area-fraction", str(fraction)]
    r, wall = C.run_result(cmd)
    r.update(size_mm=size, process_wall_s=round(wall, 1))
    return r


def describe(r):
    text = (f"{r['size_mm']:g} mm {r['solver']}: {r['n_particles']} spheres, {r['n_contacts']} contacts, {r['status']}, "
            f"{r['iterations']} iterations, run {r['wall_s']:.1f} s, process {r['process_wall_s']:.1f} s, peak {r['peak_mb']:.0f} MB, "
            f"strains {r['strain_x'] * 1e6:.0f} / {r['strain_y'] * 1e6:.0f} / {r['strain_z'] * 1e6:.0f} e-6, broken {r['broken_pct']}")
    if r.get("factorizations") is not None:
        text += (f"; {r['factorizations']} factorizations in {r['factor_wall_s']:.1f} s "
                 f"({r['factor_wall_s'] / max(r['factorizations'], 1):.2f} s each), factor {r['factor_nonzeros']:.3g} entries")
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[12.0, 15.0, 20.0])
    ap.add_argument("--solvers", nargs="+", choices=["adr", "implicit"], default=["adr", "implicit"])
    ap.add_argument("--aggregate-area-fraction", type=float, default=0.2)
    ap.add_argument("--steps-per-decade", type=float, default=2.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    rows = []
    for size in a.sizes_mm:
        here = {}
        for solver in a.solvers:
            r = one(size, solver, a.aggregate_area_fraction, a.steps_per_decade, a.seed)
            rows.append(r)
            here[solver] = r
            print(describe(r), flush=True)
        if len(here) == 2:
            print(f"{size:g} mm: implicit / adr run wall time {here['implicit']['wall_s'] / here['adr']['wall_s']:.2f}", flush=True)
    out = {"rows": rows, "aggregate_area_fraction": a.aggregate_area_fraction, "steps_per_decade": a.steps_per_decade}
    for solver in a.solvers:
        mine = [r for r in rows if r["solver"] == solver]
        if len(mine) < 2:
            continue
        b, p = C.fit_power([r["n_particles"] for r in mine], [r["wall_s"] for r in mine])
        n100 = mine[-1]["n_particles"] * (100.0 / mine[-1]["size_mm"]) ** 3
        proj = {"spheres": n100, "wall_h": p * n100 ** b / 3600, "wall_exponent": b}
        text = f"{solver}: run wall ~ spheres^{b:.2f}; a 100 mm cube ({n100:,.0f} spheres) projected at {proj['wall_h']:,.0f} h"
        if solver == "implicit":
            bf, pf = C.fit_power([r["n_particles"] for r in mine], [r["factor_nonzeros"] for r in mine])
            proj.update(factor_exponent=bf, factor_nonzeros=pf * n100 ** bf)
            text += f"; factor entries ~ spheres^{bf:.2f}, {pf * n100 ** bf:.2e} at 100 mm (L alone {pf * n100 ** bf * 8 / 1e9:,.0f} GB)"
        out[f"projected_100mm_{solver}"] = proj
        print(text, flush=True)
    if a.json:
        C.write_json(a.json, out)


main()
