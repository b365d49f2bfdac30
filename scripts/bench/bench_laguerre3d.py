#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Time and peak memory of the 3D power (Laguerre) cells, _geom.laguerre_box, against the number of spheres.

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_laguerre3d.py [--sizes 5000 20000 50000]
        [--repeat 3] [--seed 1] [--json out/bench_laguerre3d.json]

The spheres: a face-centred cubic lattice of spacing 2 Rmax (Rmax = 0.48 mm) in a cube,
radii uniform in [Rmin, Rmax] (Rmin = 0.32 mm) and every centre moved at random by up to
Rmax - r, so no two spheres overlap, in a random arrangement of about
0.45 packing density, made in no time at every size (the packer, `_geom.pack_box`, takes
about a minute at 50k spheres and is timed by bench_packing3d.py). Every size runs in its own process: the wall
time is that of the call (CGAL's triangulation, the clipping, the copies to numpy), the
memory the process's peak resident size (getrusage, as /usr/bin/time -v reports it) and its
growth during the call.
"""
import argparse
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import time

try:
    import swelldem.meso  # noqa: F401
except ImportError:
    for _cand in (globals().get("__file__"), sys.argv[0] if sys.argv else None):
        if _cand and os.path.basename(_cand) == "bench_laguerre3d.py":
            _repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(_cand))))
            sys.path.insert(0, os.path.join(_repo, "py"))
            break
from swelldem import options, paths  # noqa: E402

RMAX = 0.48
RMIN = 0.32


def jittered_fcc(n_target, seed):
    """About n_target non-overlapping spheres (see the module's doc) and their cube's side [mm]."""
    import numpy as np
    cells = max(1, round((n_target / 4) ** (1 / 3)))
    side = 2 * RMAX * math.sqrt(2)  # cubic cell of the lattice of spacing 2 Rmax
    basis = np.array([[0, 0, 0], [0, 0.5, 0.5], [0.5, 0, 0.5], [0.5, 0.5, 0]])
    g = np.arange(cells)
    grid = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 1, 3)
    c = (grid + basis + 0.25).reshape(-1, 3) * side
    rng = np.random.default_rng(seed)
    r = rng.uniform(RMIN, RMAX, len(c))
    # A shift of length <= Rmax - r (uniform in that ball) keeps |c_i - c_j| >= 2 Rmax - (Rmax - r_i)
    # - (Rmax - r_j) = r_i + r_j; the centres stay at least Rmax/4 inside the cube.
    u = rng.normal(size=c.shape)
    u /= np.linalg.norm(u, axis=1)[:, None]
    c = c + u * ((RMAX - r) * rng.uniform(0, 1, len(c)) ** (1 / 3))[:, None]
    return c, r, cells * side


def child(n_target, seed):
    from swelldem.meso import _geom
    c, r, L = jittered_fcc(n_target, seed)
    _geom.lib()  # loaded before the baseline is read
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t = time.perf_counter()
    res = _geom.laguerre_box(c[:, 0], c[:, 1], c[:, 2], r, L, L, L)
    wall = time.perf_counter() - t
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    st = res["stats"]
    vol = L ** 3
    return {"spheres": len(r), "side_mm": L, "density": float(4 / 3 * math.pi * (r ** 3).sum() / vol),
            "facets": len(res["area"]), "polygon_vertices": len(res["polygon_vertices"]),
            "neighbour_pairs": st["neighbour_pairs"], "volume_sum_rel_error": abs(st["volume_sum"] - vol) / vol,
            "wall_s": wall, "peak_rss_mib": peak / 1024, "rss_growth_mib": (peak - base) / 1024}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", nargs="+", type=int, default=[5000, 20000, 50000], help="spheres (about)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per size (seeds seed..seed+repeat-1)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", default=os.path.join(paths.REPO_DIR, "out", "bench_laguerre3d.json"))
    ap.add_argument("--child", nargs=2, type=int, help=argparse.SUPPRESS)
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    if args.child:
        print(json.dumps(child(*args.child)))
        return 0
    with options.refuse_bad("bench_laguerre3d.py"):  # every option before any work, exit 2
        for s in args.sizes:
            options.integer("sizes", s, lo=1, hi=10_000_000)
        options.integer("repeat", args.repeat, lo=1)
        options.integer("seed", args.seed, lo=0, hi=2 ** 32 - 1)
        options.output_file("json", args.json)
    rows = []
    print("| spheres | cube mm | density | facets | facets/sphere | wall s (median) | peak RSS MiB | growth MiB |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in args.sizes:
        runs = []
        for k in range(args.repeat):
            p = subprocess.run([sys.executable, os.path.abspath(__file__), "--child", str(n), str(args.seed + k)],
                               capture_output=True, text=True, check=True)
            runs.append(json.loads(p.stdout.strip().splitlines()[-1]))
        w = statistics.median(x["wall_s"] for x in runs)
        row = dict(runs[0], wall_s_median=w, wall_s_all=[x["wall_s"] for x in runs],
                   peak_rss_mib=max(x["peak_rss_mib"] for x in runs),
                   rss_growth_mib=max(x["rss_growth_mib"] for x in runs))
        rows.append(row)
        print(f"| {row['spheres']} | {row['side_mm']:.2f} | {row['density']:.3f} | {row['facets']} | "
              f"{2 * row['facets'] / row['spheres']:.2f} | {w:.3f} | {row['peak_rss_mib']:.0f} | "
              f"{row['rss_growth_mib']:.0f} |", flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
    with open(args.json, "w") as f:
        json.dump({"cpu_count": os.cpu_count(), "repeat": args.repeat, "rows": rows}, f, indent=2)
    print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
