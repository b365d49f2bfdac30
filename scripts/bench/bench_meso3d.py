#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Generation time and peak memory of a 3D mesostructure (swelldem.meso.generate, dim 3) against the cube's side.

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_meso3d.py [--sizes-mm 10 20 30 40]
        [--seed 1] [--json out/bench_meso3d.json]

The default parameters (the paper's grading, 35 % aggregate by volume, Rmax 0.48 mm). A cube too
small for the grading (10 mm: the 4.75-10 mm fraction needs 11 mm with the wall gaps) runs its
packing and facets without aggregates, and the row says so. Every size runs in its own process: the
wall time is that of generate(), the memory the process's peak resident size (getrusage).
"""
import argparse
import json
import os
import resource
import time

import _common as C  # noqa: E402  (puts py/ on the path)
from swelldem import options  # noqa: E402


def one(size, seed):
    from swelldem import meso
    meso._geom.lib()
    p = meso.MesoParameters(dim=3, width_mm=size, height_mm=size, depth_mm=size)
    note = "default grading"
    try:
        p.validate()
    except meso.MesoParameterError as e:
        p, note = p.replace(aggregate_area_fraction=0.0), f"no aggregates ({e.name} refused)"
    t = time.perf_counter()
    a = meso.generate(p, seed=seed)
    wall = time.perf_counter() - t
    s = a.summary()
    return {"size_mm": size, "note": note, "spheres": a.n_particles, "aggregates": a.n_aggregates,
            "aggregate_volume_fraction": s["aggregate_volume_fraction"], "packing_density": a.packing_density,
            "contacts": a.n_contacts, "coordination": a.mean_coordination, "timings_s": s["timings_s"],
            "wall_s": wall, "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[10, 20, 30, 40])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default=None)
    ap.add_argument("--one", type=float, default=None, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one is not None:
        print(json.dumps(one(a.one, a.seed)))
        return
    with options.refuse_bad("bench_meso3d.py"):  # every option before any work, exit 2
        for size in a.sizes_mm:
            # the parameters' own bound: at most 1e6 spheres by W H D / (4/3 pi Rmin^3), a 52 mm cube
            options.number("sizes-mm", size, lo=0.96, hi=52, lo_incl=True, hi_incl=True, unit="mm")
        options.integer("seed", a.seed, lo=0, hi=2 ** 63 - 1)
        if a.json is not None:
            options.output_file("json", a.json)
    print("| cube mm | spheres | aggregates | aggregate vol. fraction | packing density | contacts | coordination | "
          "aggregates s | packing s | Laguerre s | labelling s | wall s | peak MB | note |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for size in a.sizes_mm:
        try:
            st = C.run_plain_child(os.path.abspath(__file__), ["--one", size, "--seed", a.seed])
        except RuntimeError as e:
            print(f"| {size:g} | failed: {e} |", flush=True)
            continue
        rows.append(st)
        t = st["timings_s"]
        print(f"| {size:g} | {st['spheres']} | {st['aggregates']} | {st['aggregate_volume_fraction']:.4f} | "
              f"{st['packing_density']:.4f} | {st['contacts']} | {st['coordination']:.2f} | {t['aggregates']:.1f} | "
              f"{t['packing']:.1f} | {t['laguerre']:.1f} | {t['labelling']:.1f} | {st['wall_s']:.1f} | "
              f"{st['peak_mb']:.0f} | {st['note']} |", flush=True)
    if a.json:
        C.write_json(a.json, rows)


if __name__ == "__main__":
    main()
