#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Generate a concrete mesostructure and write DIR/mesostructure.json, .png and assembly.npz.

Runs with Python or under YADE (sys.argv then holds this script and its arguments):

    /usr/bin/python3 scripts/make_mesostructure.py --size-mm 30 30 --seed 1 --out out/meso
    scripts/yade-swelldem -n -x scripts/make_mesostructure.py --size-mm 30 30 --seed 1 --out out/meso

Lengths on the command line are in mm (thickness in m); the saved assembly is in SI metres.
"""
import argparse
import json
import os
import sys
import time

try:
    import swelldem.meso  # noqa: F401
except ImportError:
    # Under YADE, __file__ is the yade launcher and sys.argv[0] this script.
    for _cand in (globals().get("__file__"), sys.argv[0] if sys.argv else None):
        if _cand and os.path.basename(_cand) == "make_mesostructure.py":
            sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(_cand))), "py"))
            break
from swelldem import meso, options  # noqa: E402


def _fractions(text):
    out = []
    for part in text.split(","):
        lo, hi = part.split("-")
        out.append((float(lo), float(hi)))
    return tuple(out)


def _floats(text):
    return tuple(float(v) for v in text.split(","))


def parse_args(argv):
    d = meso.MesoParameters()
    ap = argparse.ArgumentParser(prog="make_mesostructure.py", description=__doc__.split("\n")[0])
    ap.add_argument("--size-mm", nargs=2, type=float, metavar=("W", "H"), default=(d.width_mm, d.height_mm),
                    help="specimen width and height [mm] (default 100 100)")
    ap.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    ap.add_argument("--out", required=True, help="output folder (created if missing)")
    ap.add_argument("--rmax-mm", type=float, default=d.rmax_mm, help="largest disc radius [mm] (default 0.48)")
    ap.add_argument("--rmin-ratio", type=float, default=d.rmin_ratio, help="Rmin / Rmax [-] (default 2/3)")
    ap.add_argument("--aggregate-fraction", type=float, default=d.aggregate_area_fraction,
                    help=f"aggregate area fraction [-] (default {d.aggregate_area_fraction})")
    ap.add_argument("--fractions-mm", type=_fractions, default=d.sieve_fractions_mm,
                    help="sieve fractions [mm], e.g. 2.4-4.75,4.75-10 (default)")
    ap.add_argument("--shares", type=_floats, default=d.fraction_shares,
                    help="area share of each fraction, e.g. 0.4,0.6 (default)")
    ap.add_argument("--min-gap-mm", type=float, default=d.min_gap_mm, help="mortar gap between aggregates [mm]")
    ap.add_argument("--wall-gap-mm", type=float, default=d.wall_gap_mm, help="gap aggregate-specimen side [mm]")
    ap.add_argument("--thickness-m", type=float, default=d.thickness_m, help="out-of-plane thickness b [m] (default 1)")
    ap.add_argument("--contact-gap-ratio", type=float, default=d.contact_gap_ratio,
                    help="contact when gap <= ratio x Rmax (default 0.05)")
    ap.add_argument("--label-rule", choices=meso.params.LABEL_RULES, default=d.label_rule,
                    help="aggregate disc rule: centre inside the polygon (default) or whole disc inside")
    ap.add_argument("--no-png", action="store_true", help="skip the picture")
    return ap.parse_args(argv)


def main(argv=None):
    t0 = time.perf_counter()
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        options.output_folder("out", args.out)
    except options.OptionError as e:
        print(f"make_mesostructure.py: {e}", file=sys.stderr)
        return 2
    try:
        params = meso.MesoParameters(
            width_mm=args.size_mm[0], height_mm=args.size_mm[1], rmax_mm=args.rmax_mm,
            rmin_ratio=args.rmin_ratio, aggregate_area_fraction=args.aggregate_fraction,
            sieve_fractions_mm=args.fractions_mm, fraction_shares=args.shares,
            min_gap_mm=args.min_gap_mm, wall_gap_mm=args.wall_gap_mm, thickness_m=args.thickness_m,
            contact_gap_ratio=args.contact_gap_ratio, label_rule=args.label_rule).validate()
        assembly = meso.generate(params, seed=args.seed)
    except (meso.MesoParameterError, meso.AggregatePlacementError) as e:
        print(f"make_mesostructure.py: {e}", file=sys.stderr)
        return 2
    os.makedirs(args.out, exist_ok=True)
    npz = assembly.save(os.path.join(args.out, "assembly.npz"))
    png = None
    if not args.no_png:
        png = meso.plot_mesostructure(assembly, os.path.join(args.out, "mesostructure.png"))
    summary = assembly.summary()
    summary["wall_s"] = assembly.stats["wall_s"]
    summary["script_wall_s"] = time.perf_counter() - t0
    summary["parameters"] = assembly.parameters
    summary["files"] = {"assembly": os.path.basename(npz), "png": png and os.path.basename(png)}
    with open(os.path.join(args.out, "mesostructure.json"), "w") as f:
        json.dump(summary, f, indent=2)
    fa = summary["facet_area_m2"]

    def fmt(k):
        v = fa[k]
        return "-" if v["mean"] is None else f"{v['min'] * 1e4:.2f}/{v['mean'] * 1e4:.2f}/{v['max'] * 1e4:.2f}"

    print(f"mesostructure {args.size_mm[0]:g} x {args.size_mm[1]:g} mm, seed {args.seed}: "
          f"{summary['n_particles']} discs ({summary['n_aggregate_particles']} aggregate), "
          f"{summary['n_aggregates']} aggregates, aggregate area fraction "
          f"{summary['aggregate_area_fraction']:.3f}, packing density {summary['packing_density']:.3f}, "
          f"coordination {summary['mean_coordination']:.2f}")
    cb = summary["contacts_by_kind"]
    print(f"contacts MORTAR {cb['MORTAR']}, ITZ {cb['ITZ']}, AGG {cb['AGG']}; facet area min/mean/max "
          f"[1e-4 m2] MORTAR {fmt('MORTAR')}, ITZ {fmt('ITZ')}, AGG {fmt('AGG')} "
          f"(paper, mortar: 6.4/7.4/9.6)")
    print(f"generated in {summary['wall_s']:.2f} s; wrote {args.out}/mesostructure.json, "
          f"{os.path.basename(npz)}" + (", mesostructure.png" if png else ""))
    return 0


if __name__ == "__main__":
    rc = main()
    if rc:
        sys.exit(rc)
