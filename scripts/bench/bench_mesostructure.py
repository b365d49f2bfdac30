#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Benchmark of the mesostructure generator on the default 100 x 100 mm specimen.

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_mesostructure.py [--repeat 3] [--json FILE]

Prints the wall time of every phase (aggregates, packing, Laguerre, labelling), the
counts and the figures of docs/mesostructure.md, and writes them as JSON
(default out/bench_mesostructure.json). Target: under 60 s on a 2-core machine.
"""
import argparse
import json
import os
import statistics
import sys
import time

try:
    import swelldem.meso  # noqa: F401
except ImportError:
    for _cand in (globals().get("__file__"), sys.argv[0] if sys.argv else None):
        if _cand and os.path.basename(_cand) == "bench_mesostructure.py":
            _repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(_cand))))
            sys.path.insert(0, os.path.join(_repo, "py"))
            break
from swelldem import meso, options, paths  # noqa: E402

TARGET_S = 60.0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3, help="generations to time (seeds 1..N)")
    ap.add_argument("--size-mm", nargs=2, type=float, default=(100.0, 100.0), metavar=("W", "H"))
    ap.add_argument("--json", default=os.path.join(paths.REPO_DIR, "out", "bench_mesostructure.json"))
    with options.refuse_bad("bench_mesostructure.py"):  # every option before any work (NaN, infinity), exit 2
        args = ap.parse_args(sys.argv[1:] if argv is None else argv)
        options.output_file("json", args.json)
        options.integer("repeat", args.repeat, lo=1)
        options.numbers("size_mm", args.size_mm, count=2, lo=0, unit="mm")
        meso.MesoParameters(width_mm=args.size_mm[0], height_mm=args.size_mm[1]).validate()  # the generator's own checks
    runs = []
    for seed in range(1, args.repeat + 1):
        t = time.perf_counter()
        a = meso.generate(seed=seed, width_mm=args.size_mm[0], height_mm=args.size_mm[1])
        wall = time.perf_counter() - t
        s = a.summary()
        s["wall_s_outer"] = wall
        runs.append(s)
        ph = s["timings_s"]
        print(f"seed {seed}: {wall:.2f} s (aggregates {ph['aggregates']:.3f}, packing {ph['packing']:.3f}, "
              f"laguerre {ph['laguerre']:.3f}, labelling {ph['labelling']:.3f}); "
              f"{s['n_particles']} discs ({s['n_aggregate_particles']} aggregate), {s['n_aggregates']} aggregates, "
              f"{s['n_contacts']} contacts {s['contacts_by_kind']}, density {s['packing_density']:.4f}, "
              f"coordination {s['mean_coordination']:.3f}, aggregate fraction {s['aggregate_area_fraction']:.3f}")
        for k in meso.KIND_NAMES:
            v = s["facet_area_m2"][k]
            if v["mean"] is not None:
                print(f"    facet area {k:6s} min/mean/max = {v['min'] * 1e4:.2f} / {v['mean'] * 1e4:.2f} / "
                      f"{v['max'] * 1e4:.2f} x 1e-4 m2")
    walls = [r["wall_s_outer"] for r in runs]
    worst = max(walls)
    result = {
        "size_mm": list(args.size_mm),
        "repeat": args.repeat,
        "wall_s_median": statistics.median(walls),
        "wall_s_max": worst,
        "target_s": TARGET_S,
        "within_target": worst < TARGET_S,
        "cpu_count": os.cpu_count(),
        "runs": runs,
        "paper_table_3_5_mortar_facet_area_m2": {"min": 6.4e-4, "mean": 7.4e-4, "max": 9.6e-4},
    }
    print(f"median {result['wall_s_median']:.2f} s, max {worst:.2f} s per 100 x 100 mm specimen "
          f"(target < {TARGET_S:g} s): {'OK' if result['within_target'] else 'TOO SLOW'}")
    os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
    with open(args.json, "w") as f:
        json.dump(result, f, indent=2)
    print(f"wrote {args.json}")
    return 0 if result["within_target"] else 1


if __name__ == "__main__":
    sys.exit(main())
