# SPDX-License-Identifier: GPL-2.0-or-later
"""The same ASR swelling test at several constant temperatures (issue 15, figure c): expansion
curves on one PNG, their values in a CSV, a Markdown table of the times and strains they reach.

    /usr/bin/python3 scripts/temperature_study.py --out out/temperature

Runs scripts/swelling_test.py --scenario asr-fine --temperature-c T for each T through the study
runner (swelldem.study: --jobs local Dask workers, or a running scheduler's with --scheduler; a
run that finished with the same settings is kept), each into DIR/T<T>C/ with its log DIR/T<T>C.log,
then writes DIR/expansion_vs_temperature.png, DIR/expansion_vs_temperature.csv and
DIR/expansion_vs_temperature.md. The options are checked before any run.
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper, report, scenario, study  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--temperatures-c", type=float, nargs="+", default=[23.0, 38.0, 60.0],
                help="constant temperatures of the runs (Larive's tests: 23, 38, 60) [C]")
ap.add_argument("--size-mm", type=float, nargs=2, default=(30.0, 30.0), metavar=("W", "H"), help="specimen size [mm]")
ap.add_argument("--seed", type=int, default=1, help="mesostructure seed (the same specimen at every temperature)")
ap.add_argument("--out", default="out/temperature", help="output folder")
ap.add_argument("--jobs", type=int, default=1, help="runs at a time: local Dask workers, one thread each [-]")
ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT) instead of local workers")
scenario.add_solver_argument(ap)
args = ap.parse_args()


def run_name(T):
    return f"T{T:g}C"


with options.refuse_bad("temperature_study.py"):
    options.output_folder("out", args.out)
    options.integer("jobs", args.jobs, lo=1)
    if len(set(args.temperatures_c)) != len(args.temperatures_c):
        options.bad("temperatures_c", tuple(args.temperatures_c), "distinct temperatures")
    tests = {T: scenario.SwellingTest(scenario="asr-fine", temperature_c=T, size_mm=tuple(args.size_mm), seed=args.seed, solver=args.solver,
                                      out=os.path.join(args.out, run_name(T))) for T in args.temperatures_c}
    for t in tests.values():
        t.validate()

runs = [study.Run(run_name(T), {"scenario": "asr-fine", "temperature_c": float(T), "size_mm": tuple(args.size_mm), "seed": args.seed,
                                  "solver": args.solver}) for T in args.temperatures_c]
with options.refuse_bad("temperature_study.py"):
    study.check(runs, args.out)  # a finished run of other settings in the folder: before any work
if not study.run_study(runs, args.out, jobs=args.jobs, scheduler=args.scheduler, prog="temperature_study"):
    sys.exit("temperature_study.py: stopped; call it again with the same options to go on")
results = {}
for T in args.temperatures_c:
    results[T] = report.load_results(os.path.join(args.out, run_name(T), "results.json"))
    if results[T]["status"] != "finished":
        sys.exit(f"temperature_study.py: the run at {T:g} C did not finish ({results[T]['status'][:200]}); "
                 f"see {os.path.join(args.out, run_name(T))}.log")

# the kinetics each run used, from the kind's own parameters as results.json records them
tau_c0, tau_l0, _ = paper.KINETICS["asr"]
T0 = results[args.temperatures_c[0]]["temperature"]["per_kind"]["MORTAR"]["referenceTemperature_K"]


def taus(T_c):
    T = T_c + scenario.KELVIN
    return tau_c0 * math.exp(5400 * (1 / T - 1 / T0)), tau_l0 * math.exp(9400 * (1 / T - 1 / T0))


def larive(t, tc, tl):
    t = np.asarray(t, dtype=float)
    return (1 - np.exp(-t / tc)) / (1 + np.exp(-(t - tl) / tc))


def time_to(t, e, level):
    """First time [day] the expansion reaches `level` (linear in log time between steps)."""
    i = int(np.argmax(e >= level))
    if e[i] < level:
        return float("nan")
    if i == 0:
        return float(t[0])
    a = (level - e[i - 1]) / (e[i] - e[i - 1])
    return float(math.exp(math.log(t[i - 1]) + a * (math.log(t[i]) - math.log(t[i - 1]))))


os.makedirs(args.out, exist_ok=True)
base = os.path.join(args.out, "expansion_vs_temperature")
times = report.mean_expansion(results[args.temperatures_c[0]])[0]
with open(base + ".csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["time_days"] + [f"expansion_{T:g}C_1e-6" for T in args.temperatures_c])
    curves = {T: report.mean_expansion(results[T])[1] for T in args.temperatures_c}
    for i, t in enumerate(times):
        w.writerow([f"{t:.6g}"] + [f"{curves[T][i] * 1e6:.3f}" for T in args.temperatures_c])

rows = []
for T in args.temperatures_c:
    t, e = report.mean_expansion(results[T])
    tc, tl = taus(T)
    final = e[-1]
    rows.append({"T_C": T, "tau_c_d": tc, "tau_L_d": tl, "t10_d": time_to(t, e, 0.1 * final), "t50_d": time_to(t, e, 0.5 * final),
                 "t90_d": time_to(t, e, 0.9 * final), "final_1e-6": final * 1e6,
                 "broken_pct": report.broken_share_pct(results[T]),
                 "wall_s": results[T]["wall_s"]})
with open(base + ".md", "w") as f:
    r0 = results[args.temperatures_c[0]]
    f.write(f"ASR-fine, {r0['config']['size_mm'][0]:g} x {r0['config']['size_mm'][1]:g} mm, seed {args.seed}, "
            f"{r0['behaviour']}, damage {'on' if r0['damage'] else 'off'}, {r0['n_particles']} discs; expansion = mean of the "
            f"x and y swelling strains; t10/t50/t90: times at 10/50/90 % of the run's final expansion; kinetics' T0 = "
            f"{T0 - scenario.KELVIN:g} C.\n\n")
    f.write("| T [C] | tau_c(T) [day] | tau_L(T) [day] | t10 [day] | t50 [day] | t90 [day] | final expansion [1e-6] "
            "| broken contacts [%] | wall [s] |\n|---|---|---|---|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r['T_C']:g} | {r['tau_c_d']:.0f} | {r['tau_L_d']:.0f} | {r['t10_d']:.0f} | {r['t50_d']:.0f} | {r['t90_d']:.0f} "
                f"| {r['final_1e-6']:.0f} | {r['broken_pct']:.1f} | {r['wall_s']:.0f} |\n")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, (ax, axn) = plt.subplots(1, 2, figsize=(12, 4.6))
colors = plt.cm.plasma(np.linspace(0.0, 0.8, len(args.temperatures_c)))
eps_inf = r0["config"]["eps_inf"]
for T, c in zip(args.temperatures_c, colors):
    t, e = report.mean_expansion(results[T])
    tc, tl = taus(T)
    ax.semilogx(t, e * 1e6, "o-", ms=3, color=c, label=f"{T:g} C: specimen")
    axn.semilogx(t, e / e[-1], "o-", ms=3, color=c, label=f"{T:g} C: specimen / its final value")
    axn.semilogx(t, larive(t, tc, tl), "--", color=c, label=f"{T:g} C: Larive xi(t) (tau_c {tc:.0f} d, tau_L {tl:.0f} d)")
ax.set_xlabel("time [day]")
ax.set_ylabel("expansion (mean of x and y swelling strains) [1e-6]")
ax.set_title(f"ASR-fine at constant temperatures (eps_inf of mortar {eps_inf * 1e6:g}e-6)")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
axn.set_xlabel("time [day]")
axn.set_ylabel("normalised expansion, swelling ratio xi [-]")
axn.set_title("shape: specimen against the mortar's free kinetics")
axn.grid(True, which="both", alpha=0.3)
axn.legend(fontsize=7)
fig.tight_layout()
fig.savefig(base + ".png", dpi=120)
print(open(base + ".md").read())
print(f"temperature_study: {base}.png, .csv, .md")
