# SPDX-License-Identifier: GPL-2.0-or-later
"""The same ASR swelling test at several relative humidities: expansion curves and the final
expansion against h on one PNG, their values in a CSV, a Markdown table.

    /usr/bin/python3 scripts/humidity_study.py --out out/humidity --jobs 2

Two ways to hold a specimen at a humidity h, each a run of scripts/swelling_test.py --scenario
asr-fine through the study runner (swelldem.study: --jobs local Dask workers, or a running
scheduler's with --scheduler; a finished run with the same settings is kept):
- held: every particle at h from the start, every face sealed (--humidity-initial h): the
  swelling at a uniform, constant h, which the model scales by f(h) = h^m;
- stored: saturated at the start, every face exposed to h (--humidity-face x- h ...): a
  specimen cast wet and stored at h, which dries from its faces and shrinks while it swells.
h = 1 is one run (both are the saturated specimen). Each run goes into DIR/<mode>-h<100 h>/ with
its log beside it; then DIR/expansion_vs_humidity.png, .csv and .md. The options are checked
before any run.
"""
import argparse
import csv
import os
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, report, scenario, study  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("--humidities", type=float, nargs="+", default=[0.6, 0.8, 0.9, 1.0], help="relative humidities h of the runs [-]")
ap.add_argument("--modes", nargs="+", choices=("held", "stored"), default=["held", "stored"],
                help="held: uniform h, sealed; stored: saturated, faces exposed to h")
ap.add_argument("--size-mm", type=float, nargs=2, default=(70.0, 70.0), metavar=("W", "H"),
                help="specimen section (a laboratory prism's: ASTM C1293's is 75 x 75 mm) [mm]")
ap.add_argument("--seed", type=int, default=1, help="mesostructure seed (the same specimen at every humidity)")
ap.add_argument("--humidity-exponent", type=float, default=scenario.SwellingTest().humidity_exponent, help="m of f(h) = h^m [-]")
ap.add_argument("--no-damage", dest="damage", action="store_false", help="contacts never break")
ap.add_argument("--out", default="out/humidity", help="output folder")
ap.add_argument("--jobs", type=int, default=1, help="runs at a time: local Dask workers, one thread each [-]")
ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (tcp://HOST:PORT) instead of local workers")
scenario.add_solver_argument(ap)
args = ap.parse_args()
FACES = ("x-", "x+", "y-", "y+")


def run_name(mode, h):
    return "saturated" if h == 1.0 else f"{mode}-h{round(100 * h):d}"


def settings(mode, h):
    s = {"scenario": "asr-fine", "size_mm": tuple(args.size_mm), "seed": args.seed, "solver": args.solver, "damage": args.damage,
         "humidity_exponent": args.humidity_exponent}
    if h != 1.0:
        if mode == "held":
            s["humidity_initial"] = h
        else:
            s["humidity_faces"] = {f: h for f in FACES}
    return s


with options.refuse_bad("humidity_study.py"):
    options.output_folder("out", args.out)
    options.integer("jobs", args.jobs, lo=1)
    if len(set(args.humidities)) != len(args.humidities):
        options.bad("humidities", tuple(args.humidities), "distinct humidities")
    keys = []
    for mode in args.modes:
        for h in args.humidities:
            options.number("humidities", h, lo=0, hi=1, hi_incl=True)
            if (run_name(mode, h), h) not in [(run_name(m, x), x) for m, x in keys]:
                keys.append((mode, h))
    for mode, h in keys:
        scenario.SwellingTest(**settings(mode, h), out=os.path.join(args.out, run_name(mode, h))).validate()

runs = [study.Run(run_name(m, h), settings(m, h)) for m, h in keys]
with options.refuse_bad("humidity_study.py"):
    study.check(runs, args.out)
if not study.run_study(runs, args.out, jobs=args.jobs, scheduler=args.scheduler, prog="humidity_study"):
    sys.exit("humidity_study.py: stopped; call it again with the same options to go on")
results = {}
for m, h in keys:
    r = report.load_results(os.path.join(args.out, run_name(m, h), "results.json"))
    if r["status"] != "finished":
        sys.exit(f"humidity_study.py: {run_name(m, h)} did not finish ({r['status'][:200]}); see {os.path.join(args.out, run_name(m, h))}.log")
    results[(m, h)] = r
saturated = next((r for (m, h), r in results.items() if h == 1.0), None)


def mean_h(res):
    return res["humidity"]["mean_h"]["specimen"][-1] if "humidity" in res else 1.0


os.makedirs(args.out, exist_ok=True)
base = os.path.join(args.out, "expansion_vs_humidity")
m_exp = args.humidity_exponent
e_sat = report.mean_expansion(saturated)[1][-1] if saturated else float("nan")
rows = []
for (mode, h), r in results.items():
    e = report.mean_expansion(r)[1]
    rows.append({"run": run_name(mode, h), "mode": "saturated" if h == 1.0 else mode, "h": h, "final_1e-6": e[-1] * 1e6,
                 "max_1e-6": e.max() * 1e6, "ratio": e[-1] / e_sat, "f_h": h ** m_exp, "h_end": mean_h(r), "broken_pct": report.broken_share_pct(r),
                 "wall_s": r["wall_s"]})
rows.sort(key=lambda r: (r["mode"], r["h"]))
with open(base + ".csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(list(rows[0]))
    for r in rows:
        w.writerow([f"{v:.6g}" if isinstance(v, float) else v for v in r.values()])
with open(base + ".md", "w") as f:
    f.write(f"ASR-fine, {args.size_mm[0]:g} x {args.size_mm[1]:g} mm, seed {args.seed}, {saturated['behaviour'] if saturated else ''}, "
            f"damage {'on' if args.damage else 'off'}, f(h) = h^{m_exp:g}; expansion = mean of the x and y swelling strains at "
            f"{rows[0] and results[keys[0]]['times_days'][-1]:g} days; ratio: against the saturated run; h at the end: the "
            "specimen's volume mean.\n\n")
    f.write("| run | h | final expansion [1e-6] | largest [1e-6] | ratio to saturated | h^m | h at the end | broken [%] | wall [s] |\n"
            "|---|---|---|---|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r['run']} | {r['h']:g} | {r['final_1e-6']:.0f} | {r['max_1e-6']:.0f} | {r['ratio']:.3f} | {r['f_h']:.3f} "
                f"| {r['h_end']:.3f} | {r['broken_pct']:.1f} | {r['wall_s']:.0f} |\n")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, (ax, axr) = plt.subplots(1, 2, figsize=(12.5, 4.8))
hs = sorted({h for _, h in keys})
colors = dict(zip(hs, plt.cm.viridis(np.linspace(0.9, 0.1, len(hs)))))
for (mode, h), r in sorted(results.items(), key=lambda kv: (kv[0][1], kv[0][0])):
    t, e = report.mean_expansion(r)
    style = "-" if mode == "held" or h == 1.0 else "--"
    ax.semilogx(t, e * 1e6, style, marker="o", ms=2.5, color=colors[h], label=f"{run_name(mode, h)}")
ax.axhline(0, color="0.5", lw=0.8)
ax.set(xlabel="time [day]", ylabel="expansion (mean of x and y strains) [1e-6]",
       title="ASR-fine at constant humidity (solid: held, dashed: stored)")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
hh = np.linspace(0.5, 1.0, 101)
axr.plot(hh, hh ** m_exp, "k-", lw=1, label=f"f(h) = h^{m_exp:g} (the model's factor)")
for mode, marker in (("held", "o"), ("stored", "s")):
    pts = [(r["h"], r["ratio"]) for r in rows if r["mode"] in (mode, "saturated")]
    if len(pts) > 1 and mode in args.modes:
        x, y = zip(*sorted(pts))
        axr.plot(x, y, marker + "-" if mode == "held" else marker + "--", label=f"{mode}: final expansion / saturated")
axr.axvspan(0.80, 0.85, color="tab:orange", alpha=0.2, label="threshold of significant ASR expansion reported\nat 80-85 % RH (docs/moisture.md)")
axr.axhline(0, color="0.5", lw=0.8)
axr.set(xlabel="relative humidity h [-]", ylabel="expansion / saturated expansion [-]", title="final expansion against humidity")
axr.grid(True, alpha=0.3)
axr.legend(fontsize=8)
fig.tight_layout()
fig.savefig(base + ".png", dpi=120)
print(open(base + ".md").read())
print(f"humidity_study: {base}.png, .csv, .md")
