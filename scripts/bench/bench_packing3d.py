#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Time, density and peak memory of the 3D sphere packing, _geom.pack_box, against the cube's side.

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_packing3d.py [--sizes-mm 10 20 30 40]
        [--seed 1] [--json out/bench_packing3d.json]

Rmax = 0.48 mm, Rmin = 0.32 mm. Every size runs in its own process: the wall time is that of the
call, the memory the process's peak resident size (getrusage).
"""
import argparse
import json
import os
import resource
import time

import _common as C  # noqa: E402  (puts py/ on the path)
from swelldem import options  # noqa: E402

RMAX = 0.48
RMIN = 0.32


def one(size, seed):
    from swelldem.meso import _geom
    _geom.lib()
    t = time.perf_counter()
    x, y, z, r, st = _geom.pack_box(size, size, size, RMIN, RMAX, seed)
    wall = time.perf_counter() - t
    st.update(size_mm=size, wall_s=wall, peak_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
    return st


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[10, 20, 30])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default=None)
    ap.add_argument("--one", type=float, default=None, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one is not None:
        print(json.dumps(one(a.one, a.seed)))
        return
    with options.refuse_bad("bench_packing3d.py"):  # every option before any work, exit 2
        for size in a.sizes_mm:
            # pack_box needs rmax <= side / 2 and refuses more than 5e7 spheres (about a 285 mm cube)
            options.number("sizes-mm", size, lo=2 * RMAX, hi=250, lo_incl=True, hi_incl=True, unit="mm")
        options.integer("seed", a.seed, lo=0, hi=2 ** 64 - 1)
        if a.json is not None:
            options.output_file("json", a.json)
    print("| size mm | spheres | density | target | dropped | sweeps | near-contacts/sphere | wall s | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|")
    rows = []
    for size in a.sizes_mm:
        st = C.run_plain_child(os.path.abspath(__file__), ["--one", size, "--seed", a.seed])
        rows.append(st)
        print(f"| {size:g} | {st['n']} | {st['density']:.4f} | {st['target_density']:.4f} | {st['removed']} | "
              f"{st['sweeps']} | {st['near_contacts_per_sphere']:.2f} | {st['wall_s']:.2f} | {st['peak_mb']:.0f} |",
              flush=True)
    if a.json:
        C.write_json(a.json, rows)


if __name__ == "__main__":
    main()
