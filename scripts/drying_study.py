# SPDX-License-Identifier: GPL-2.0-or-later
"""A specimen drying from two opposite faces beside the same specimen sealed: where it cracks,
what the skin and the core do.

    /usr/bin/python3 scripts/drying_study.py --out out/drying100 --jobs 2

Runs scripts/swelling_test.py twice through the study runner (swelldem.study; a finished run
with the same settings is kept): DIR/sealed/ and DIR/drying/ (--humidity-face x- H --humidity-face
x+ H), both with VTK files every few steps. Then DIR/drying_vs_sealed.png: the crack maps of both
at --map-day, with the drying faces marked; the profiles across the specimen (bands parallel to
the drying faces) of h, of the mean stress sigma_yy (the discs' Love-Weber stress from the ParaView
files) and of the broken share; and the expansion of both against time. DIR/drying_vs_sealed.md
and .csv hold the numbers. The options are checked before any run.
"""
import argparse
import csv
import glob
import os
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import meso, options, paper, report, study  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--scenario", choices=tuple(paper.SCENARIOS), default="asr-fine")
ap.add_argument("--size-mm", type=float, nargs=2, default=(100.0, 100.0), metavar=("W", "H"),
                help="specimen size; it dries across W, from its x- and x+ faces [mm]")
ap.add_argument("--ambient", type=float, default=0.5, help="ambient relative humidity of the two faces [-]")
ap.add_argument("--seed", type=int, default=1, help="mesostructure seed")
ap.add_argument("--map-day", type=float, default=None, help="time of the crack maps and profiles (default: the run's end) [day]")
ap.add_argument("--bands", type=int, default=10, help="bands across W for the profiles [-]")
ap.add_argument("--out", default="out/drying", help="output folder")
ap.add_argument("--jobs", type=int, default=1, help="runs at a time: local Dask workers [-]")
ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler instead of local workers")
args = ap.parse_args()

common = {"scenario": args.scenario, "size_mm": tuple(args.size_mm), "seed": args.seed, "vtk_every": 5}
runs = [study.Run("sealed", dict(common)),
        study.Run("drying", {**common, "humidity_faces": {"x-": args.ambient, "x+": args.ambient}})]
with options.refuse_bad("drying_study.py"):
    options.output_folder("out", args.out)
    options.integer("jobs", args.jobs, lo=1)
    options.integer("bands", args.bands, lo=2)
    for r in runs:
        r.test(args.out).validate()
    study.check(runs, args.out)
if not study.run_study(runs, args.out, jobs=args.jobs, scheduler=args.scheduler, prog="drying_study"):
    sys.exit("drying_study.py: stopped; call it again with the same options to go on")
res = {}
for r in runs:
    res[r.name] = report.load_results(os.path.join(args.out, r.name, "results.json"))
    if res[r.name]["status"] != "finished":
        sys.exit(f"drying_study.py: {r.name} did not finish ({res[r.name]['status'][:200]})")

import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402


def snapshots(name):
    """{time [day]: (body ids, sigma_yy [Pa])} of a run's ParaView particles."""
    out = {}
    for f in sorted(glob.glob(os.path.join(args.out, name, "vtk", "particles_*.vtp"))):
        rd = vtk.vtkXMLPolyDataReader()
        rd.SetFileName(f)
        rd.Update()
        p = rd.GetOutput()
        t = float(vtk_to_numpy(p.GetFieldData().GetArray("TimeValue"))[0])
        out[t] = (vtk_to_numpy(p.GetCellData().GetArray("id")), vtk_to_numpy(p.GetCellData().GetArray("stress"))[:, 4])
    return out


assembly = meso.load(os.path.join(args.out, "drying", "assembly.npz"))
x = np.asarray(assembly.x)
area = np.asarray(assembly.cell_area_m2)
edges = np.linspace(0, assembly.width_m, args.bands + 1)
band = np.clip(np.digitize(x, edges) - 1, 0, args.bands - 1)
centres_mm = 0.5 * (edges[:-1] + edges[1:]) * 1e3


def band_mean(values, ids):
    v = np.zeros(args.bands)
    for k in range(args.bands):
        s = band[ids] == k
        v[k] = np.sum(values[s] * area[ids][s]) / np.sum(area[ids][s])
    return v


def broken_share(name, step):
    b = np.load(os.path.join(args.out, name, "contact_breaks.npz"))
    seg = b["segment_m"]
    xm = 0.5 * (seg[:, 0] + seg[:, 2])
    kb = np.clip(np.digitize(xm, edges) - 1, 0, args.bands - 1)
    broken = (b["break_step"] >= 0) & (b["break_step"] <= step)
    return np.array([100 * broken[kb == k].mean() for k in range(args.bands)])


t_end = res["drying"]["times_days"][-1]
day = args.map_day or t_end
step = int(np.argmin(np.abs(np.array(res["drying"]["times_days"]) - day)))
day = res["drying"]["times_days"][step]
hum = np.load(os.path.join(args.out, "drying", "humidity.npz"))
snaps = {n: snapshots(n) for n in ("sealed", "drying")}
profile_days = sorted(snaps["drying"])

os.makedirs(args.out, exist_ok=True)
base = os.path.join(args.out, "drying_vs_sealed")
with open(base + ".csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["run", "t_days", "quantity"] + [f"x={c:.3g}mm" for c in centres_mm])
    for t in profile_days:
        k = int(np.argmin(np.abs(hum["times_days"] - t)))
        w.writerow(["drying", f"{t:.6g}", "h [-]"] + [f"{v:.4f}" for v in band_mean(hum["h"][k].astype(float), np.arange(len(x)))])
        for n in ("sealed", "drying"):
            if t in snaps[n]:
                ids, syy = snaps[n][t]
                w.writerow([n, f"{t:.6g}", "sigma_yy [MPa]"] + [f"{v:.4f}" for v in band_mean(syy / 1e6, ids)])
    for n in ("sealed", "drying"):
        w.writerow([n, f"{day:.6g}", "broken [%]"] + [f"{v:.3f}" for v in broken_share(n, step)])


def kinds_broken(r, k):
    return {n: 100 * r["per_kind"][n]["broken"][k] / max(1, r["n_contacts_by_kind"][n]) for n in paper.KIND_NAMES}


skin = (centres_mm < 0.2 * assembly.width_m * 1e3) | (centres_mm > 0.8 * assembly.width_m * 1e3)
with open(base + ".md", "w") as f:
    f.write(f"{report.LABEL.get(args.scenario, args.scenario)}, {args.size_mm[0]:g} x {args.size_mm[1]:g} mm, seed {args.seed}, "
            f"{res['drying']['behaviour']}, damage {'on' if res['drying']['damage'] else 'off'}; drying: x- and x+ exposed to h "
            f"{args.ambient:g} from the start (t = {res['drying']['times_days'][0]:g} d); skin: the outer fifth on each side.\n\n")
    f.write("| run | expansion at the end [1e-6] | largest expansion [1e-6] | broken MORTAR / ITZ / AGG [%] at "
            f"{day:.4g} d | broken in the skin / core [%] | wall [s] |\n|---|---|---|---|---|---|\n")
    for n in ("sealed", "drying"):
        t, e = report.mean_expansion(res[n])
        kb = kinds_broken(res[n], step)
        bs = broken_share(n, step)
        f.write(f"| {n} | {e[-1] * 1e6:.0f} | {e.max() * 1e6:.0f} | {kb['MORTAR']:.1f} / {kb['ITZ']:.1f} / {kb['AGG']:.1f} | "
                f"{bs[skin].mean():.1f} / {bs[~skin].mean():.1f} | {res[n]['wall_s']:.0f} |\n")
    f.write("\nProfiles across x (band centres in mm), drying run: h and sigma_yy [MPa] (tension > 0) at each exported time.\n\n")
    f.write("| t [d] | quantity | " + " | ".join(f"{c:.0f}" for c in centres_mm) + " |\n|---|---|" + "---|" * args.bands + "\n")
    for t in profile_days:
        k = int(np.argmin(np.abs(hum["times_days"] - t)))
        f.write(f"| {t:.4g} | h | " + " | ".join(f"{v:.2f}" for v in band_mean(hum["h"][k].astype(float), np.arange(len(x)))) + " |\n")
        ids, syy = snaps["drying"][t]
        f.write(f"| {t:.4g} | sigma_yy | " + " | ".join(f"{v:.2f}" for v in band_mean(syy / 1e6, ids)) + " |\n")

# the crack maps at the chosen time, each by the report's own drawing
for n in ("sealed", "drying"):
    from swelldem.report import broken_at, load_breaks, plot_crack_map  # noqa: E402
    plot_crack_map(args.out, res[n], assembly, broken_at(load_breaks(os.path.join(args.out, n)), step), step=step,
                   name=f"crack_map_{n}.png")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

fig = plt.figure(figsize=(15, 10.5))
gs = fig.add_gridspec(2, 6, height_ratios=[1.25, 1])
for col, n in enumerate(("sealed", "drying")):
    ax = fig.add_subplot(gs[0, 3 * col:3 * col + 3])
    ax.imshow(mpimg.imread(os.path.join(args.out, f"crack_map_{n}.png")))
    ax.set_axis_off()
    ax.set_title(n, fontsize=12)
colors = plt.cm.viridis(np.linspace(0.0, 0.85, len(profile_days)))
ax = fig.add_subplot(gs[1, 0:2])
for t, c in zip(profile_days, colors):
    k = int(np.argmin(np.abs(hum["times_days"] - t)))
    ax.plot(centres_mm, band_mean(hum["h"][k].astype(float), np.arange(len(x))), "o-", ms=3, color=c, label=f"{t:.3g} d")
ax.set(xlabel="x [mm] (drying faces at both ends)", ylabel="h [-]", title="relative humidity across the specimen")
ax.legend(fontsize=7, ncol=2)
ax.grid(alpha=0.3)
ax = fig.add_subplot(gs[1, 2:4])
for t, c in zip(profile_days, colors):
    ids, syy = snaps["drying"][t]
    ax.plot(centres_mm, band_mean(syy / 1e6, ids), "o-", ms=3, color=c, label=f"drying {t:.3g} d")
ids, syy = snaps["sealed"][max(snaps["sealed"])]
ax.plot(centres_mm, band_mean(syy / 1e6, ids), "k--", lw=1, label=f"sealed {max(snaps['sealed']):.3g} d")
ax.axhline(0, color="0.5", lw=0.8)
ax.set(xlabel="x [mm]", ylabel="sigma_yy [MPa] (tension > 0)", title="stress parallel to the faces, band means")
ax.legend(fontsize=7, ncol=2)
ax.grid(alpha=0.3)
ax = fig.add_subplot(gs[1, 4:6])
for n, style in (("sealed", "k-"), ("drying", "b-")):
    t, e = report.mean_expansion(res[n])
    ax.semilogx(t, e * 1e6, style, label=f"{n}: expansion")
ax.axhline(0, color="0.5", lw=0.8)
ax.set(xlabel="time [day]", ylabel="expansion (mean of x and y) [1e-6]", title="expansion; broken share across x at the map's time")
inset = ax.inset_axes([0.08, 0.55, 0.4, 0.38])
for n, style in (("sealed", "ko-"), ("drying", "bo-")):
    inset.plot(centres_mm, broken_share(n, step), style, ms=2, lw=1)
inset.set_xlabel("x [mm]", fontsize=7)
inset.set_ylabel("broken [%]", fontsize=7)
inset.tick_params(labelsize=6)
ax.legend(fontsize=8, loc="lower left")
ax.grid(alpha=0.3, which="both")
fig.suptitle(report._title(res["drying"]), fontsize=10)
fig.tight_layout()
fig.savefig(base + ".png", dpi=110)
print(open(base + ".md").read())
print(f"drying_study: {base}.png, .md, .csv")
