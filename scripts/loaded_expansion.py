# SPDX-License-Identifier: GPL-2.0-or-later
"""ASR expansion of a 3D prism under a uniaxial compressive stress (the experiment a 2D section
cannot reproduce): expansion along and across the load and the volumetric expansion against the
stress, beside the trend Multon and Toutlemonde measured on loaded cylinders.

    /usr/bin/python3 scripts/loaded_expansion.py --out out/loaded [--stresses-mpa 0 1 2.5]
        [--size-mm 12 12 24] [--steps-per-decade 4] [--t-start 28] [--seed 1] [--strength-scale 1] [--solver adr|implicit] (default adr)

Each stress S runs scripts/swelling_test.py --dim 3 --scenario asr-fine --behaviour viscoelastic
(damage on unless --no-damage) --boundary-z stress:-S twice: reactive (the run's eps_inf) and non-reactive (eps_inf
0, the same specimen under the same load: its elastic and creep strains). As in the laboratory,
where a loaded companion of non-reactive concrete gives the creep to subtract, the ASR expansion
is the reactive strain minus the non-reactive one, per direction: along the load (z), across it
(the mean of x and y) and the volume change. Every run starts at --t-start (28 days by default):
the load, like the laboratory's, acts on cured concrete, and the swelling counted is the part
after it. --strength-scale S multiplies the tensile strength of every contact kind in every run
(the prism's compressive strength is S times the paper's 6.2 MPa). The runs go through the study
runner (swelldem.study: --jobs local Dask workers, or a running scheduler's with --scheduler),
each into DIR/<run>/ with its log DIR/<run>.log; a run that finished with the same settings is
kept, a finished run of other settings stops the script before any work. Writes DIR/loaded_expansion.png, .csv and .md.
"""
import argparse
import csv
import os
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper, report, scenario, study  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
# 0, 1 and 2.5 MPa: the prism's compressive strength at the paper's contact strengths is 6.2 MPa
# (scripts/prism_strength.py), below the laboratory's 10 and 20 MPa
ap.add_argument("--stresses-mpa", type=float, nargs="+", default=[0.0, 1.0, 2.5],
                help="uniaxial compressive stresses on the z faces, >= 0 (compression) [MPa]")
ap.add_argument("--size-mm", type=float, nargs=3, default=(12.0, 12.0, 24.0), metavar=("W", "H", "D"),
                help="prism size; the load acts along D (z) [mm]")
ap.add_argument("--steps-per-decade", type=float, default=4.0, help="physical steps a decade of log time [1/decade]")
ap.add_argument("--aggregate-area-fraction", type=float, default=0.2,
                help="aggregate volume fraction (below the default 0.35 so that a prism under 25 mm places its grains) [-]")
ap.add_argument("--t-start", type=float, default=28.0,
                help="age at which the load is applied and the run starts, > 0 (Multon and Toutlemonde loaded at 28 days) [day]")
ap.add_argument("--seed", type=int, default=1, help="mesostructure seed (the same specimen in every run)")
# 1: the paper's Table 3.5 contact strengths. The prism's compressive strength is proportional to
# the scale (6.2 MPa at 1, 18.7 MPa at 3, scripts/prism_strength.py); 0 5 10 MPa runs at
# --strength-scale 3 (docs/scenarios.md, "A prism under a uniaxial load")
ap.add_argument("--strength-scale", type=float, default=1.0,
                help="factor on the paper's Table 3.5 tensile strengths of every contact kind, in every run, > 0 [-]")
ap.add_argument("--no-damage", action="store_true",
                help="contacts never break: the model is then linear, and the ASR expansion under any load is the free one "
                     "(superposition): the load's effect is the cracking's")
ap.add_argument("--out", default="out/loaded", help="output folder")
ap.add_argument("--jobs", type=int, default=1, help="runs at a time: local Dask workers, one thread each [-]")
ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT) instead of local workers")
# The ADR by default: under a platen load a cracking step of the 12 x 12 x 24 mm prism (5 MPa, day
# 2800 to 5000) took the ADR 7,350 iterations, while the implicit solver's relaxation phases did
# not settle its rounds within fallbackIterations, and its fallback relaxation had not finished the
# step after 83,861 iterations (docs/scenarios.md, "A prism under a uniaxial load").
scenario.add_solver_argument(ap, default="adr")
args = ap.parse_args()


def run_name(stress, reactive):
    return f"S{stress:g}MPa_{'reactive' if reactive else 'inert'}"


def common(stress, reactive):
    return dict(dim=3, scenario="asr-fine", behaviour="viscoelastic", damage=not args.no_damage, size_mm=tuple(args.size_mm), seed=args.seed,
                solver=args.solver, steps_per_decade=args.steps_per_decade, strength_scale=args.strength_scale, t_start_days=args.t_start, aggregate_area_fraction=args.aggregate_area_fraction,
                boundary_z=f"stress:{-stress * 1e6:g}" if stress > 0 else "free",
                **({} if reactive else {"eps_inf": 0.0}))


with options.refuse_bad("loaded_expansion.py"):
    options.output_folder("out", args.out)
    options.integer("jobs", args.jobs, lo=1)
    for s in args.stresses_mpa:
        options.number("stresses_mpa", s, lo=0, lo_incl=True, unit="MPa")
    options.number("t_start", args.t_start, lo=0, unit="day")
    options.number("strength_scale", args.strength_scale, lo=0, unit="-")
    if len(set(args.stresses_mpa)) != len(args.stresses_mpa):
        options.bad("stresses_mpa", tuple(args.stresses_mpa), "distinct stresses")
    runs = {}
    for s in args.stresses_mpa:
        for reactive in (True, False):
            if s == 0 and not reactive:
                continue  # an unloaded inert specimen does not move
            t = scenario.SwellingTest(out=os.path.join(args.out, run_name(s, reactive)), **common(s, reactive))
            t.validate()
            runs[s, reactive] = t

with options.refuse_bad("loaded_expansion.py"):
    study_runs = [study.Run(run_name(s, reactive), common(s, reactive)) for (s, reactive) in runs]
    study.check(study_runs, args.out)  # a finished run of other settings in the folder: before any work
if not study.run_study(study_runs, args.out, jobs=args.jobs, scheduler=args.scheduler, prog="loaded_expansion"):
    sys.exit("loaded_expansion.py: stopped; call it again with the same options to go on")
results = {}
for (s, reactive), test in runs.items():
    results[s, reactive] = report.load_results(os.path.join(test.out, "results.json"))
    if results[s, reactive]["status"] != "finished":
        sys.exit(f"loaded_expansion.py: the run {run_name(s, reactive)} did not finish ({results[s, reactive]['status'][:200]}); "
                 f"see {test.out}.log")


def strains(res):
    """(days, along z, across: mean of x and y, volume) [-] of a run."""
    return (np.array(res["times_days"]), np.array(res["swelling_strain_z"]),
            0.5 * (np.array(res["swelling_strain_x"]) + np.array(res["swelling_strain_y"])), np.array(res["swelling_strain_volume"]))


asr = {}  # per stress: days, ASR expansion along, across, volume (reactive minus inert)
for s in args.stresses_mpa:
    t, z, xy, v = strains(results[s, True])
    if s > 0:
        _, z0, xy0, v0 = strains(results[s, False])
        z, xy, v = z - z0, xy - xy0, v - v0
    asr[s] = (t, z, xy, v)

os.makedirs(args.out, exist_ok=True)
base = os.path.join(args.out, "loaded_expansion")
r0 = results[args.stresses_mpa[0], True]
free = asr[min(args.stresses_mpa)]
with open(base + ".csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["stress_MPa", "time_days", "asr_along_1e-6", "asr_across_1e-6", "asr_volume_1e-6", "total_along_1e-6", "total_across_1e-6"])
    for s in args.stresses_mpa:
        t, z, xy, v = asr[s]
        _, tz, txy, _ = strains(results[s, True])
        for i in range(len(t)):
            w.writerow([f"{s:g}", f"{t[i]:.6g}", f"{z[i] * 1e6:.3f}", f"{xy[i] * 1e6:.3f}", f"{v[i] * 1e6:.3f}", f"{tz[i] * 1e6:.3f}",
                        f"{txy[i] * 1e6:.3f}"])
with open(base + ".md", "w") as f:
    f.write(f"ASR-fine, viscoelastic, damage {'off' if args.no_damage else 'on'}, 3D prism {' x '.join(f'{v:g}' for v in args.size_mm)} mm (load along the "
            f"last side, z), seed {args.seed}, {r0['n_particles']} spheres, aggregate fraction {args.aggregate_area_fraction:g}, "
            f"{args.steps_per_decade:g} steps a decade, solver {args.solver}, tensile strengths {args.strength_scale:g} x the paper's "
            f"(--strength-scale), loaded and started at day {args.t_start:g}. ASR expansion = reactive strain minus the strain of "
            f"the same specimen without swelling under the same load (eps_inf 0: its elastic and creep strains), at "
            f"{free[0][-1]:g} days; across = mean of the x and y strains; volume = the volume change.\n\n")
    f.write("| stress [MPa] | ASR along the load [1e-6] | ASR across [1e-6] | ASR volume [1e-6] | along / free | across / free "
            "| volume / free | broken contacts [%] | wall [s] |\n|---|---|---|---|---|---|---|---|---|\n")
    for s in args.stresses_mpa:
        t, z, xy, v = asr[s]
        res = results[s, True]
        # the concrete's contacts (MORTAR, ITZ, AGG), not the platens' (which never break)
        broken = 100 * sum(res["per_kind"][k]["broken"][-1] for k in paper.KIND_NAMES) / max(1, sum(res["n_contacts_by_kind"][k] for k in paper.KIND_NAMES))
        f.write(f"| {s:g} | {z[-1] * 1e6:.0f} | {xy[-1] * 1e6:.0f} | {v[-1] * 1e6:.0f} | {z[-1] / free[1][-1]:.2f} | "
                f"{xy[-1] / free[2][-1]:.2f} | {v[-1] / free[3][-1]:.2f} | {broken:.1f} | {res['wall_s']:.0f} |\n")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, (ax, axs) = plt.subplots(1, 2, figsize=(12, 4.8))
colors = plt.cm.viridis(np.linspace(0.0, 0.8, len(args.stresses_mpa)))
for c, s in zip(colors, args.stresses_mpa):
    t, z, xy, v = asr[s]
    ax.semilogx(t, z * 1e6, "-", color=c, label=f"{s:g} MPa: along the load")
    ax.semilogx(t, xy * 1e6, "--", color=c, label=f"{s:g} MPa: across")
    ax.semilogx(t, v * 1e6, ":", color=c, lw=2, label=f"{s:g} MPa: volume")
ax.set_xlabel("time [day]")
ax.set_ylabel("ASR expansion (reactive minus inert under the same load) [1e-6]")
ax.set_title("ASR expansion of a loaded prism")
ax.grid(alpha=0.3)
top = max(max(asr[s][3].max(), asr[s][1].max(), asr[s][2].max()) for s in args.stresses_mpa) * 1e6
ax.set_ylim(top=1.35 * top)  # room above the curves for the legend
ax.legend(fontsize=7, ncol=len(args.stresses_mpa), loc="upper left")
S = np.array(args.stresses_mpa)
for key, i, mark in (("along the load", 1, "o-"), ("across", 2, "s--"), ("volume", 3, "^:")):
    axs.plot(S, [asr[s][i][-1] / free[i][-1] for s in args.stresses_mpa], mark, label=f"model: {key}")
axs.axhline(1.0, color="0.5", lw=0.8)
axs.set_xlabel("uniaxial compressive stress [MPa]")
axs.set_ylabel(f"final ASR expansion / the unloaded prism's (day {free[0][-1]:g}) [-]")
axs.set_title("Multon & Toutlemonde (2006): along the load reduced, moved across,\nvolume about constant whatever the stress",
              fontsize=9)
axs.grid(alpha=0.3)
axs.legend(fontsize=8)
fig.suptitle(f"ASR-fine, viscoelastic, damage {'off' if args.no_damage else 'on'}, 3D prism {' x '.join(f'{v:g}' for v in args.size_mm)} mm, seed {args.seed}, "
             f"{args.solver}, strengths x {args.strength_scale:g}, loaded from day {args.t_start:g}", fontsize=10)
fig.tight_layout()
fig.savefig(base + ".png", dpi=120)
print(f"loaded_expansion.py: {base}.png, .csv, .md")
