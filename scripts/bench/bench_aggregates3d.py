#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Which cube sizes hold the default grading of polyhedral aggregates, over seeds, and how long the
draw and the placement take (swelldem.meso.aggregates3d; no packing, no facets).

    /usr/bin/python3 scripts/bench/bench_aggregates3d.py [--sizes-mm 20 25 30] [--seeds 0 29] [--json F]

For every size, seeds first..last (the generator's seeds: the aggregates' stream of
swelldem.meso.generator.seed_streams, as swelldem.meso.generate draws it). Prints one row a size: seeds
placed, the aggregates and the volume fraction reached (mean over the placed seeds), mean draw and
placement times. MIN_RELIABLE_SIZE_3D_MM in aggregates3d.py quotes this table.
"""
import argparse
import time

import _common as C  # noqa: E402  (puts py/ on the path)
import numpy as np  # noqa: E402

from swelldem import meso, options  # noqa: E402
from swelldem.meso import aggregates3d  # noqa: E402
from swelldem.meso.generator import seed_streams  # noqa: E402


def one(size, seed):
    p = meso.MesoParameters(dim=3, width_mm=size, height_mm=size, depth_mm=size).validate()
    rng = seed_streams(seed)[0]
    t = time.perf_counter()
    aggs = aggregates3d.draw_polyhedra(p, rng)
    t_draw = time.perf_counter() - t
    t = time.perf_counter()
    try:
        placed = aggregates3d.place_polyhedra(p, aggs, rng, seed=seed)
    except aggregates3d.AggregatePlacementError:
        placed = None
    t_place = time.perf_counter() - t
    frac = None if placed is None else sum(a.volume for a in placed) / size ** 3
    return {"size_mm": size, "seed": seed, "aggregates": len(aggs), "placed": placed is not None,
            "volume_fraction": frac, "draw_s": t_draw, "place_s": t_place}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[20, 25, 30])
    ap.add_argument("--seeds", type=int, nargs=2, default=[0, 29], metavar=("FIRST", "LAST"))
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    with options.refuse_bad("bench_aggregates3d.py"):  # every option before any work, exit 2
        for size in a.sizes_mm:
            # the grading's 10 mm sieve with the 0.5 mm wall gaps needs 11 mm; 52 mm is the sphere bound
            options.number("sizes-mm", size, lo=11, hi=52, lo_incl=True, hi_incl=True, unit="mm")
        options.integer("seeds", a.seeds[0], lo=0, hi=2 ** 63 - 1)
        options.integer("seeds", a.seeds[1], lo=a.seeds[0], hi=2 ** 63 - 1)
        if a.json is not None:
            options.output_file("json", a.json)
    print("| cube mm | seeds placed | aggregates | volume fraction | draw s | place s | failed seeds |")
    print("|---|---|---|---|---|---|---|")
    rows = []
    for size in a.sizes_mm:
        res = [one(size, s) for s in range(a.seeds[0], a.seeds[1] + 1)]
        rows += res
        ok = [r for r in res if r["placed"]]
        frac = f"{np.mean([r['volume_fraction'] for r in ok]):.4f}" if ok else "-"
        failed = [r["seed"] for r in res if not r["placed"]]
        print(f"| {size:g} | {len(ok)}/{len(res)} | {np.mean([r['aggregates'] for r in res]):.0f} | {frac} | "
              f"{np.mean([r['draw_s'] for r in res]):.1f} | {np.mean([r['place_s'] for r in res]):.1f} | "
              f"{' '.join(map(str, failed)) or '-'} |", flush=True)
    if a.json:
        C.write_json(a.json, rows)


if __name__ == "__main__":
    main()
