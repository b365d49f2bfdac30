#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Generate a concrete mesostructure and write DIR/mesostructure.json, .md, .png and assembly.npz.

Runs with Python or under YADE (sys.argv then holds this script and its arguments):

    /usr/bin/python3 scripts/make_mesostructure.py --size-mm 30 30 --seed 1 --out out/meso
    scripts/yade-swelldem -n -x scripts/make_mesostructure.py --size-mm 30 30 --seed 1 --out out/meso
    /usr/bin/python3 scripts/make_mesostructure.py --dim 3 --size-mm 30 30 30 --seed 1 --out out/meso3d

A 3D box also writes facets.png (its facet sizes against a 2D section's) and mesostructure.vtm
(spheres, facets and aggregates for ParaView). Lengths on the command line are in mm (thickness
in m); the saved assembly is in SI metres.
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
from swelldem.meso import paraview, plot3d  # noqa: E402


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
    ap.add_argument("--dim", type=int, choices=(2, 3), default=2, help="2: a section of discs (default); 3: a box of spheres")
    ap.add_argument("--size-mm", nargs="+", type=float, metavar="L", default=None,
                    help="specimen width and height [mm] (2D, default 100 100), or width, height and depth (3D)")
    ap.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    ap.add_argument("--out", required=True, help="output folder (created if missing)")
    ap.add_argument("--rmax-mm", type=float, default=d.rmax_mm, help="largest disc radius [mm] (default 0.48)")
    ap.add_argument("--rmin-ratio", type=float, default=d.rmin_ratio, help="Rmin / Rmax [-] (default 2/3)")
    ap.add_argument("--aggregate-fraction", type=float, default=d.aggregate_area_fraction,
                    help=f"aggregate area fraction [-], the volume fraction in 3D (default {d.aggregate_area_fraction})")
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
    ap.add_argument("--no-png", action="store_true", help="skip the pictures")
    args = ap.parse_args(argv)
    if args.size_mm is None:
        args.size_mm = (d.width_mm, d.height_mm) + ((d.depth_mm,) if args.dim == 3 else ())
    return args


def main(argv=None):
    t0 = time.perf_counter()
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        options.output_folder("out", args.out)
    except options.OptionError as e:
        print(f"make_mesostructure.py: {e}", file=sys.stderr)
        return 2
    if len(args.size_mm) != args.dim:
        print(f"make_mesostructure.py: swelldem: size_mm = {' '.join(f'{v:g}' for v in args.size_mm)} is out of range; "
              f"allowed: {args.dim} lengths in mm for --dim {args.dim} ({'W H' if args.dim == 2 else 'W H D'})",
              file=sys.stderr)
        return 2
    try:
        params = meso.MesoParameters(
            dim=args.dim, width_mm=args.size_mm[0], height_mm=args.size_mm[1],
            depth_mm=args.size_mm[2] if args.dim == 3 else meso.MesoParameters.depth_mm, rmax_mm=args.rmax_mm,
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
    summary = assembly.summary()
    files = {"assembly": os.path.basename(npz)}
    if args.dim == 3:
        # The facet sizes of a box against a section of the same packing parameters, without
        # aggregates (the kinds only label the facets; the sizes are the packing's).
        section = meso.generate(params.replace(dim=2, aggregate_area_fraction=0.0), seed=args.seed)
        summary["facet_size_mm"] = {"3d": plot3d.facet_size_table(assembly), "2d_section": plot3d.facet_size_table(section),
                                    "2d_section_mean_coordination": section.mean_coordination,
                                    "definition": "2D: facet length; 3D: 2 sqrt(facet area / pi)"}
        files["paraview"] = os.path.basename(paraview.write_vtm(assembly, os.path.join(args.out, "mesostructure.vtm")))
    if not args.no_png:
        files["png"] = os.path.basename(meso.plot_mesostructure(assembly, os.path.join(args.out, "mesostructure.png")))
        if args.dim == 3:
            files["facets_png"] = os.path.basename(plot3d.plot_facet_sizes(assembly, section,
                                                                           os.path.join(args.out, "facets.png")))
    summary["wall_s"] = assembly.stats["wall_s"]
    summary["script_wall_s"] = time.perf_counter() - t0
    summary["parameters"] = assembly.parameters
    files["markdown"] = "mesostructure.md"
    summary["files"] = files
    with open(os.path.join(args.out, "mesostructure.json"), "w") as f:
        json.dump(summary, f, indent=2)
    with open(os.path.join(args.out, "mesostructure.md"), "w") as f:
        f.write(markdown(summary))
    fa = summary["facet_area_m2"]
    unit, scale = ("1e-4 m2", 1e4) if args.dim == 2 else ("mm2", 1e6)

    def fmt(k):
        v = fa[k]
        return "-" if v["mean"] is None else f"{v['min'] * scale:.2f}/{v['mean'] * scale:.2f}/{v['max'] * scale:.2f}"

    size = " x ".join(f"{v:g}" for v in args.size_mm)
    what, share = (("discs", "area") if args.dim == 2 else ("spheres", "volume"))
    print(f"mesostructure {size} mm, seed {args.seed}: "
          f"{summary['n_particles']} {what} ({summary['n_aggregate_particles']} aggregate), "
          f"{summary['n_aggregates']} aggregates, aggregate {share} fraction "
          f"{summary[f'aggregate_{share}_fraction']:.3f}, packing density {summary['packing_density']:.3f}, "
          f"coordination {summary['mean_coordination']:.2f}")
    cb = summary["contacts_by_kind"]
    print(f"contacts MORTAR {cb['MORTAR']}, ITZ {cb['ITZ']}, AGG {cb['AGG']}; facet area min/mean/max "
          f"[{unit}] MORTAR {fmt('MORTAR')}, ITZ {fmt('ITZ')}, AGG {fmt('AGG')}"
          + (" (paper, mortar: 6.4/7.4/9.6)" if args.dim == 2 else ""))
    print(f"generated in {summary['wall_s']:.2f} s; wrote {args.out}/mesostructure.json, mesostructure.md, "
          + ", ".join(v for k, v in files.items() if k not in ("markdown",)))
    return 0


def markdown(s):
    """The summary as Markdown tables: counts, fractions, facets."""
    d3 = s["dim"] == 3
    size = [s["width_m"], s["height_m"]] + ([s["depth_m"]] if d3 else [])
    share = "volume" if d3 else "area"
    lines = [f"# {'3D' if d3 else '2D'} mesostructure {' x '.join(f'{v * 1e3:g}' for v in size)} mm, seed {s['seed']}", "",
             "| quantity | value |", "|---|---|",
             f"| {'spheres' if d3 else 'discs'} (aggregate / mortar) | {s['n_particles']} ({s['n_aggregate_particles']} / "
             f"{s['n_mortar_particles']}) |",
             f"| packing density | {s['packing_density']:.4f} |",
             f"| aggregates (per sieve fraction) | {s['n_aggregates']} ({', '.join(map(str, s.get('aggregates_by_fraction', [])))}) |",
             f"| aggregate {share} fraction (target) | {s.get(f'aggregate_{share}_fraction', 0):.4f} "
             f"({s.get(f'aggregate_{share}_fraction_target', 0):.4f}) |",
             f"| aggregate {share} share per fraction | "
             f"{', '.join(f'{v:.3f}' for v in s.get(f'aggregate_{share}_by_fraction', []))} |",
             f"| contacts (MORTAR / ITZ / AGG) | {s['n_contacts']} ({s['contacts_by_kind']['MORTAR']} / "
             f"{s['contacts_by_kind']['ITZ']} / {s['contacts_by_kind']['AGG']}) |",
             f"| mean coordination | {s['mean_coordination']:.3f} |",
             f"| generation wall time [s] | {s['wall_s']:.1f} |", ""]
    fs = s.get("facet_size_mm")
    if fs:
        lines += ["Facet size [mm] (2D: facet length; 3D: 2 sqrt(facet area / pi)); the 2D section has the same "
                  "packing parameters, without aggregates.", "",
                  "| contacts | n | mean | 5 % | 50 % | 95 % |", "|---|---|---|---|---|---|"]
        for label, tab in (("3D, all", fs["3d"]["all"]), ("3D, MORTAR", fs["3d"]["MORTAR"]), ("3D, ITZ", fs["3d"]["ITZ"]),
                           ("3D, AGG", fs["3d"]["AGG"]), ("2D section, all", fs["2d_section"]["all"])):
            if tab["n"]:
                lines.append(f"| {label} | {tab['n']} | {tab['mean']:.3f} | {tab['q05']:.3f} | {tab['q50']:.3f} | "
                             f"{tab['q95']:.3f} |")
        lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":
    rc = main()
    if rc:
        sys.exit(rc)
