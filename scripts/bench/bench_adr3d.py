#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Cost of a 3D box's swelling test under the ADR against the cube's side: set-up and run wall
time, peak memory, iterations, spheres and contacts, strains and broken shares.

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_adr3d.py [--sizes-mm 15 20 25]
        [--aggregate-area-fraction 0.2] [--steps-per-decade 2] [--seed 1] [--json out/bench_adr3d.json]

Each size is one run of scripts/bench/bench_implicit_damage.py (--dim 3 --solver adr, ISR
viscoelastic with damage) in its own process on one thread, which reports its own peak resident
size. The power law of the run's wall time against the spheres is fitted and a 100 mm cube's
projected from it (the spheres scale with the volume). The aggregate fraction is below the
default 35 % so that cubes under 25 mm place their grains (docs/mesostructure.md).
"""
import argparse
import json
import os
import subprocess
import time

import _common as C  # noqa: E402  (puts py/ on the path)

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bench_implicit_damage.py")


def one(size, fraction, spd, seed):
    cmd = [C.LAUNCHER, "-n", "-j", "1", "-x", SCRIPT, "--dim", "3", "--size-mm", str(size), str(size), str(size),
           "--solver", "adr", "--scenario", "isr", "--behaviour", "viscoelastic", "--seed", str(seed),
           "--steps-per-decade", str(spd), "--aggregate-area-fraction", str(fraction)]
    t = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    out, err = p.stdout, p.stderr
    wall = time.time() - t
    lines = [ln for ln in out.splitlines() if ln.startswith("RESULT ")]
    if not lines:
        raise RuntimeError(f"{' '.join(cmd)} failed: {(err.strip().splitlines() or ['?'])[-1]}")
    r = json.loads(lines[-1][len("RESULT "):])
    r.update(size_mm=size, process_wall_s=round(wall, 1))
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[15.0, 20.0, 25.0])
    ap.add_argument("--aggregate-area-fraction", type=float, default=0.2)
    ap.add_argument("--steps-per-decade", type=float, default=2.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    rows = []
    for size in a.sizes_mm:
        r = one(size, a.aggregate_area_fraction, a.steps_per_decade, a.seed)
        rows.append(r)
        print(f"{size:g} mm: {r['n_particles']} spheres, {r['n_contacts']} contacts, {r['status']}, {r['iterations']} iterations, "
              f"run {r['wall_s']:.1f} s, process {r['process_wall_s']:.1f} s, peak {r['peak_mb']:.0f} MB, strains "
              f"{r['strain_x'] * 1e6:.0f} / {r['strain_y'] * 1e6:.0f} / {r['strain_z'] * 1e6:.0f} e-6, broken {r['broken_pct']}",
              flush=True)
    out = {"rows": rows, "aggregate_area_fraction": a.aggregate_area_fraction, "steps_per_decade": a.steps_per_decade}
    if len(rows) >= 2:
        b, p = C.fit_power([r["n_particles"] for r in rows], [r["wall_s"] for r in rows])
        n100 = rows[-1]["n_particles"] * (100.0 / rows[-1]["size_mm"]) ** 3
        out.update(wall_exponent=b, projected_100mm={"spheres": n100, "wall_h": p * n100 ** b / 3600})
        print(f"run wall ~ spheres^{b:.2f}; a 100 mm cube ({n100:,.0f} spheres) projected at {p * n100 ** b / 3600:,.0f} h", flush=True)
    if a.json:
        C.write_json(a.json, out)


main()
