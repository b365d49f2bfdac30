# SPDX-License-Identifier: GPL-2.0-or-later
"""The same ASR swelling test at several constant temperatures (issue 15, figure c): expansion
curves on one PNG, their values in a CSV, a Markdown table of the times and strains they reach.

    /usr/bin/python3 scripts/temperature_study.py --out out/temperature

Runs scripts/swelling_test.py --scenario asr-fine --temperature-c T for each T (one YADE process
at a time, -j 1; a run whose results.json says 'finished' is not made again), each into DIR/T<T>C/,
then writes DIR/expansion_vs_temperature.png, DIR/expansion_vs_temperature.csv and
DIR/expansion_vs_temperature.md. The options are checked before any run.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper, report, scenario  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--temperatures-c", type=float, nargs="+", default=[23.0, 38.0, 60.0],
                help="constant temperatures of the runs (Larive's tests: 23, 38, 60) [C]")
ap.add_argument("--size-mm", type=float, nargs=2, default=(30.0, 30.0), metavar=("W", "H"), help="specimen size [mm]")
ap.add_argument("--seed", type=int, default=1, help="mesostructure seed (the same specimen at every temperature)")
ap.add_argument("--out", default="out/temperature", help="output folder")
scenario.add_solver_argument(ap)
args = ap.parse_args()


def run_name(T):
    return f"T{T:g}C"


with options.refuse_bad("temperature_study.py"):
    options.output_folder("out", args.out)
    if len(set(args.temperatures_c)) != len(args.temperatures_c):
        options.bad("temperatures_c", tuple(args.temperatures_c), "distinct temperatures")
    tests = {T: scenario.SwellingTest(scenario="asr-fine", temperature_c=T, size_mm=tuple(args.size_mm), seed=args.seed, solver=args.solver,
                                      out=os.path.join(args.out, run_name(T))) for T in args.temperatures_c}
    for t in tests.values():
        t.validate()

env = dict(os.environ, OMP_NUM_THREADS="1")
results = {}
for T, test in tests.items():
    path = os.path.join(test.out, "results.json")
    done = False
    if os.path.exists(path):
        with open(path) as f:
            done = json.load(f).get("status") == "finished"
    if not done:
        os.makedirs(test.out, exist_ok=True)
        cmd = [os.path.join(REPO, "scripts", "yade-swelldem"), "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"),
               "--scenario", "asr-fine", "--temperature-c", f"{T:g}", "--size-mm", *[f"{v:g}" for v in args.size_mm],
               "--seed", str(args.seed), "--out", test.out]
        t0 = time.time()
        with open(os.path.join(test.out, "log.txt"), "w") as log:
            rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
        print(f"{run_name(T)}: exit {rc}, {time.time() - t0:.0f} s", flush=True)
        if rc != 0:
            sys.exit(f"temperature_study.py: the run at {T:g} C failed; see {test.out}/log.txt")
    results[T] = report.load_results(path)

# the kinetics each run used, from the kind's own parameters as results.json records them
tau_c0, tau_l0, _ = paper.KINETICS["asr"]
T0 = results[args.temperatures_c[0]]["temperature"]["per_kind"]["MORTAR"]["referenceTemperature_K"]


def taus(T_c):
    T = T_c + scenario.KELVIN
    return tau_c0 * math.exp(5400 * (1 / T - 1 / T0)), tau_l0 * math.exp(9400 * (1 / T - 1 / T0))


def larive(t, tc, tl):
    t = np.asarray(t, dtype=float)
    return (1 - np.exp(-t / tc)) / (1 + np.exp(-(t - tl) / tc))


def expansion(res):
    """Mean of the x and y swelling strains [-] at each physical time [day]."""
    return np.array(res["times_days"]), 0.5 * (np.array(res["swelling_strain_x"]) + np.array(res["swelling_strain_y"]))


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
times = expansion(results[args.temperatures_c[0]])[0]
with open(base + ".csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["time_days"] + [f"expansion_{T:g}C_1e-6" for T in args.temperatures_c])
    curves = {T: expansion(results[T])[1] for T in args.temperatures_c}
    for i, t in enumerate(times):
        w.writerow([f"{t:.6g}"] + [f"{curves[T][i] * 1e6:.3f}" for T in args.temperatures_c])

rows = []
for T in args.temperatures_c:
    t, e = expansion(results[T])
    tc, tl = taus(T)
    final = e[-1]
    rows.append({"T_C": T, "tau_c_d": tc, "tau_L_d": tl, "t10_d": time_to(t, e, 0.1 * final), "t50_d": time_to(t, e, 0.5 * final),
                 "t90_d": time_to(t, e, 0.9 * final), "final_1e-6": final * 1e6,
                 "broken_pct": 100 * sum(results[T]["per_kind"][k]["broken"][-1] for k in paper.KIND_NAMES) /
                 max(1, sum(results[T]["n_contacts_by_kind"].values())),
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
    t, e = expansion(results[T])
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
