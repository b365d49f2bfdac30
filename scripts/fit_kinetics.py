# SPDX-License-Identifier: GPL-2.0-or-later
"""Fits the swelling parameters a user cannot measure (Larive's tau_c and tau_L, the free expansion
eps_inf that sets d_inf) so that the simulated specimen's expansion follows a laboratory curve.

  /usr/bin/python3 scripts/fit_kinetics.py --data lab.csv --scenario asr-fine --out DIR
      [--behaviour viscoelastic|elastic] [--no-damage] [--size-mm W H [D]] [--seeds 1 2 3]
      [--steps-per-decade K] [--solver implicit|adr] [--t-start DAY] [--start TAU_C TAU_L EPS_INF]
      [--fd-step 0.05] [--max-steps 25] [--jobs N | --scheduler tcp://HOST:PORT]

lab.csv: a header 'day, expansion [unit]' (unit -, 1e-6, um/m, %, mm/m) and rows of numbers; the
expansion is the specimen's linear expansion (the model's: the mean of its axes' strains). Every
evaluation is a real specimen run of swelling_test.py up to the last day of the data, made through
swelldem.study on local Dask workers (--jobs) or a scheduler's (--scheduler), a point and its
Jacobian's neighbours side by side; runs are kept in DIR/runs/, so a fit called again reuses them.
Method and uncertainty: swelldem.calibration (least squares on the values' logarithms, the
Jacobian's covariance, the spread of the values refitted on each seed).

DIR then holds fit.json (the values with their uncertainty, per seed the fit, its residuals and
the optimiser's record), fit.md, fit.csv (day, data, model per seed, residual) and fit.png (the data
against the fitted curves, and the residuals). A fit whose residuals' RMS exceeds 5 % of the data's
largest expansion is reported as a poor fit (exit status 1): the model cannot follow that curve
with these settings. Bad input (days negative or not increasing, fewer than 4 points, a curve that
falls after its maximum, a setting out of range) is refused before any run (exit status 2)."""
import argparse
import csv
import json
import os
import sys
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import calibration, options, paper, report, scenario, study  # noqa: E402


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", required=True, help="laboratory curve: CSV 'day, expansion [unit]'")
    ap.add_argument("--scenario", required=True, choices=tuple(paper.SCENARIOS), help="the swelling test whose kinetics are fitted")
    ap.add_argument("--out", required=True, help="folder of the fit (its runs in DIR/runs/)")
    ap.add_argument("--behaviour", default="viscoelastic", choices=scenario.BEHAVIOURS, help="contacts (default viscoelastic)")
    ap.add_argument("--no-damage", dest="damage", action="store_false", help="contacts never break")
    ap.add_argument("--size-mm", type=float, nargs="+", default=[20.0, 20.0], help="specimen W H (W H D with --dim 3) [mm] (default 20 20)")
    ap.add_argument("--dim", type=int, default=2, help="2 (discs) or 3 (spheres)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1], help="mesostructure seeds, one fit each [-] (default 1)")
    ap.add_argument("--steps-per-decade", type=float, default=3.0, help="physical steps per decade of log time [1/decade] (default 3)")
    scenario.add_solver_argument(ap)
    ap.add_argument("--t-start", type=float, default=1.0, help="age of the stress-free start [day] (default 1)")
    ap.add_argument("--start", type=float, nargs=3, default=None, metavar=("TAU_C", "TAU_L", "EPS_INF"),
                    help="first guess [day, day, -] (default: from the curve's shape)")
    ap.add_argument("--fd-step", type=float, default=0.05, help="relative step of the Jacobian's differences [-] (default 0.05)")
    ap.add_argument("--max-steps", type=int, default=25, help="most evaluations of the optimiser a seed [-] (default 25)")
    ap.add_argument("--jobs", type=int, default=2, help="local Dask workers without --scheduler [-] (default 2)")
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT)")
    return ap.parse_args(argv)


def check(a):
    options.output_folder("out", a.out)
    options.integer("jobs", a.jobs, lo=1)
    options.integer("max_steps", a.max_steps, lo=1)
    options.number("fd_step", a.fd_step, lo=0, hi=0.5, allowed="0 < fd_step < 0.5 [-]")
    t, y = calibration.read_curve(a.data)
    options.number("t_start", a.t_start, lo=0, hi=float(t[-1]), unit="day",
                   allowed=f"0 < t_start < {t[-1]:g} (the data's last day) [day]")
    p0 = np.array(a.start) if a.start else calibration.start_values(t, y)
    if a.start:
        for n, v in zip(calibration.NAMES, a.start):
            options.number(f"start {n}", v, lo=0)
    base = {"scenario": a.scenario, "behaviour": a.behaviour, "damage": a.damage, "size_mm": tuple(a.size_mm), "dim": a.dim,
            "steps_per_decade": a.steps_per_decade, "solver": a.solver, "t_start_days": a.t_start, "t_end_days": float(t[-1])}
    runs = [study.Run(calibration.run_name(p0, s, t), calibration.run_settings(base, p0, s, t)) for s in a.seeds]
    for s in a.seeds:
        options.integer("seeds", s, lo=0)
    if len(set(a.seeds)) != len(a.seeds):
        options.bad("seeds", tuple(a.seeds), "distinct seeds")
    study.check(runs, os.path.join(a.out, "runs"))  # the swelling test's own checks, before any run
    return t, y, p0, base


def main(argv):
    a = parse(argv)
    with options.refuse_bad("fit_kinetics.py"):
        t, y, p0, base = check(a)
    runs_dir = os.path.join(a.out, "runs")
    os.makedirs(runs_dir, exist_ok=True)
    t0 = time.time()
    fits = []
    with study.Runner(a.jobs, a.scheduler, prog="fit_kinetics") as runner:
        for seed in a.seeds:
            batch = [0]

            def evaluate(ps, seed=seed):
                runs = [study.Run(calibration.run_name(p, seed, t), calibration.run_settings(base, p, seed, t)) for p in ps]
                if not runner.run(runs, runs_dir, quiet=True):
                    sys.exit("fit_kinetics.py: stopped; call it again with the same options to go on (the runs made are kept)")
                curves = []
                for r, p in zip(runs, ps):
                    res = report.load_results(os.path.join(runs_dir, r.name, "results.json"))
                    if res["status"] != "finished":
                        sys.exit(f"fit_kinetics.py: the evaluation run {r.name} did not finish ({res['status'][:200]}); "
                                 f"see {runs_dir}/{r.name}.log")
                    curves.append(calibration.model_curve(res, t))
                batch[0] += 1
                c0 = curves[0]
                rms = float(np.sqrt(np.mean((c0 - y) ** 2)) / np.max(np.abs(y)))
                print(f"fit_kinetics: seed {seed}, batch {batch[0]} ({len(ps)} runs): tau_c {ps[0][0]:.4g} d, tau_L {ps[0][1]:.4g} d, "
                      f"eps_inf {ps[0][2]:.4g}: RMS {rms:.2%} of the largest expansion; elapsed {time.time() - t0:.0f} s", flush=True)
                return curves

            f = calibration.Fit(t, y, evaluate, fd_step=a.fd_step).run(p0, max_nfev=a.max_steps)
            f["seed"] = seed
            best = [f["values"][n] for n in calibration.NAMES]
            f["run"] = calibration.run_name(best, seed, t)
            res = report.load_results(os.path.join(runs_dir, f["run"], "results.json"))  # the fitted point's run, made by the fit
            f["curve_days"] = res["times_days"]
            f["curve"] = calibration.model_curve(res, res["times_days"]).tolist()
            fits.append(f)
    values = calibration.combine(fits)
    poor = [f["seed"] for f in fits if f["rms_relative"] > calibration.POOR_FIT_RMS]
    record = {"data": os.path.abspath(a.data), "days": t.tolist(), "expansion": y.tolist(), "settings": {**base, "seeds": a.seeds},
              "method": "scipy.optimize.least_squares (trf) on log(tau_c, tau_L, eps_inf); forward-difference Jacobian of relative "
                        f"step {a.fd_step:g}; 1-sigma from s^2 (J^T J)^-1 and the seeds' spread",
              "values": values, "fits": fits, "quality": "poor" if poor else "good",
              "poor_fit_rms": calibration.POOR_FIT_RMS, "wall_s": time.time() - t0}
    with open(os.path.join(a.out, "fit.json"), "w") as f:
        json.dump(record, f, indent=1)
    write_tables(a, t, y, fits, values, poor)
    plot(a, t, y, fits, values)
    for n in calibration.NAMES:
        v = values[n]
        print(f"fit_kinetics: {n} = {v['value']:.4g} {v['unit']} (95 %: {v['low95']:.4g} to {v['high95']:.4g})")
    if poor:
        print(f"fit_kinetics: poor fit (seeds {poor}): the residuals' RMS exceeds {calibration.POOR_FIT_RMS:.0%} of the largest expansion; "
              f"the model does not follow this curve with these settings ({a.out}/fit.png)")
        sys.exit(1)
    print(f"fit_kinetics: {a.out}/fit.md, fit.json, fit.csv, fit.png")


def write_tables(a, t, y, fits, values, poor):
    with open(os.path.join(a.out, "fit.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["day", "data_1e-6"] + [x for fi in fits for x in (f"model_seed{fi['seed']}_1e-6", f"residual_seed{fi['seed']}_1e-6")])
        for i in range(len(t)):
            w.writerow([f"{t[i]:g}", f"{y[i] * 1e6:.4f}"] + [f"{v * 1e6:.4f}" for fi in fits for v in (fi["model"][i], fi["residuals"][i])])
    lines = [f"# Kinetics fitted to {os.path.basename(a.data)}", "",
             f"{a.scenario}, {a.behaviour}, damage {'on' if a.damage else 'off'}, {' x '.join(f'{v:g}' for v in a.size_mm)} mm, "
             f"seeds {' '.join(map(str, a.seeds))}, {a.steps_per_decade:g} steps a decade, solver {a.solver}, from day {a.t_start:g}. "
             "Least squares on the logarithms of the values; uncertainty 1-sigma relative, from the Jacobian and the seeds' spread, "
             "95 % interval value x exp(+-2 sigma).", "",
             "| value | fitted | 95 % interval | sigma (Jacobian) | sigma (seeds) | per seed |", "|---|---|---|---|---|---|"]
    for n in calibration.NAMES:
        v = values[n]
        lines.append(f"| {n} [{v['unit']}] | {v['value']:.4g} | {v['low95']:.4g} to {v['high95']:.4g} | {v['sigma_jacobian_rel']:.1%} | "
                     f"{v['sigma_seeds_rel']:.1%} | {', '.join(f'{x:.4g}' for x in v['per_seed'])} |")
    lines += ["", "| seed | RMS residual / largest expansion | runs | optimiser |", "|---|---|---|---|"]
    for fi in fits:
        lines.append(f"| {fi['seed']} | {fi['rms_relative']:.2%} | {fi['evaluations']} | {fi['optimizer']['message']} |")
    lines += ["", "Poor fit: the model does not follow this curve with these settings." if poor else
              f"Good fit: residuals' RMS within {calibration.POOR_FIT_RMS:.0%} of the largest expansion.", "", "![fit](fit.png)"]
    with open(os.path.join(a.out, "fit.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def plot(a, t, y, fits, values):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, ar) = plt.subplots(2, 1, figsize=(7.5, 6.5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    ax.plot(t, y * 1e6, "ko", ms=4, label="data")
    for fi in fits:
        ax.plot(fi["curve_days"], np.array(fi["curve"]) * 1e6, ".-", label=f"model at its steps, seed {fi['seed']} "
                f"(RMS {fi['rms_relative']:.1%} at the data's days)")
        ar.plot(t, np.array(fi["residuals"]) * 1e6, "o-", ms=3, label=f"seed {fi['seed']}")
    v = values
    ax.set_title(f"{a.scenario}, {a.behaviour}, damage {'on' if a.damage else 'off'}: tau_c {v['tau_c']['value']:.3g} d, "
                 f"tau_L {v['tau_L']['value']:.3g} d, eps_inf {v['eps_inf']['value'] * 1e6:.0f}e-6", fontsize=10)
    ax.set_ylabel("linear expansion [1e-6]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ar.axhline(0, color="0.5", lw=0.8)
    ar.set_xlabel("time [day]")
    ar.set_ylabel("model - data [1e-6]")
    ar.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "fit.png"), dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1:])
