# SPDX-License-Identifier: GPL-2.0-or-later
"""Accuracy against cost of the swelling tests (issue 7): the error of the final swelling strain and
of the 5 %/95 % normal-force quantiles of each contact kind against a fine reference run, and the
wall time, when one solver setting is varied at a time (steps per decade, ADR tolerance, Kelvin
units per decade). A benchmark, not a timed test.

    /usr/bin/python3 scripts/bench/bench_accuracy.py [--scenarios isr asr-fine] [--size-mm 20]
        [--behaviour viscoelastic] [--damage] [--sweeps default reference] [--verify 6]
        [--extra '{"steps_per_decade": 5, "tolerance": 1e-5}'] [--out out/bench/accuracy] [--force]

Every configuration runs in its own YADE process (scripts/yade-swelldem -n -j 1 -x this --worker ...),
through swelldem.scenario.run, into OUT/<scenario>[-dmg]/<config>/ (results.json, plots, run.log,
bench.json). A configuration whose bench.json exists is not run again (--force reruns it), so the
tables can be rebuilt from what is on disk. Prints the tables and writes OUT/accuracy.json,
OUT/accuracy.md and OUT/accuracy.png (largest relative error against the ADR iterations of the run,
which are exact where wall times on a shared machine are not).

Definitions:
- reference: steps per decade 40, tolerance 1e-6, 2 Kelvin units a decade; default: 10, 1e-4, 1;
  the 'default' sweep changes one of the three from the default, the 'reference' sweep one from the
  reference; then the cheapest combinations whose estimated error is within 1 % and 5 % are run
  until one is verified (see candidates()); --extra adds configurations by hand;
- strain error: |eps - eps_ref| / |eps_ref| of eps = (eps_xx + eps_yy) / 2 at the last step;
  'history' is the largest such error at the times every run has (10, 100, 1000 d and the end);
- force error of a kind: |q - q_ref| / max(|q05_ref|, |q95_ref|) for q = its 5 % and 95 % quantile of
  Fn at the last step (scaled by the kind's force range, since a quantile may sit near zero);
- 'max error': the largest of the strain error and the six force errors;
- wall: the solver's wall time (scene.run_to_end of the run: ADR iterations and the per-step
  recording), without YADE's start, the mesostructure, the modulus calibration and the plots.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

THIS = next(os.path.abspath(c) for c in (sys.argv[0], globals().get("__file__"), "scripts/bench/bench_accuracy.py")
            if c and os.path.basename(c) == "bench_accuracy.py")
BENCH_DIR = os.path.dirname(THIS)
REPO = os.path.dirname(os.path.dirname(BENCH_DIR))
sys.path.insert(0, os.path.join(REPO, "py"))
from swelldem import options, paper  # noqa: E402
LAUNCHER = os.path.join(REPO, "scripts", "yade-swelldem")

DEFAULT = {"steps_per_decade": 10, "tolerance": 1e-4, "kelvin_units_per_decade": 1.0}
REFERENCE = {"steps_per_decade": 40, "tolerance": 1e-6, "kelvin_units_per_decade": 2.0}
FACTORS = {"steps_per_decade": [2, 5, 10, 20, 40],
           "tolerance": [1e-2, 1e-3, 1e-4, 1e-5, 1e-6],
           "kelvin_units_per_decade": [0.5, 1.0, 2.0, 4.0]}
SHORT = {"steps_per_decade": "N", "tolerance": "tol", "kelvin_units_per_decade": "kelvin"}
TARGETS = (0.01, 0.05)


def config_name(c):
    return f"N{c['steps_per_decade']:g}-tol{c['tolerance']:.0e}-k{c['kelvin_units_per_decade']:g}"


def configs(sweeps):
    """(label, sweep, varied factor, settings): the reference, the default, and each factor varied on
    its own from the default ('default' sweep: what changing one setting does in practice) and from
    the reference ('reference' sweep: the error that setting alone causes)."""
    out = [("reference", None, None, dict(REFERENCE)), ("default", None, None, dict(DEFAULT))]
    for sweep in sweeps:
        base = DEFAULT if sweep == "default" else REFERENCE
        for f, values in FACTORS.items():
            for v in values:
                c = dict(base, **{f: v})
                if c != base:
                    out.append((("" if sweep == "default" else "ref + ") + f"{SHORT[f]} {v:g}", sweep, f, c))
    return out


# ------------------------------------------------------------------------------------------ worker
def worker(a):
    from swelldem import scenario
    from swelldem.dem import scene
    c = json.loads(a.config)
    timing = {}
    plain = scene.run_to_end

    def timed(solver, chunk=2000, seconds=None):  # times the scenario's own solve, not a (macro) modulus calibration
        t0 = time.time()
        plain(solver, chunk, seconds)
        if solver.label == "swelldemSolver":
            timing["solve_s"] = time.time() - t0
            timing["iterations"] = int(solver.totalIterations)
            timing["steps"] = len(solver.stepIterations)
    scene.run_to_end = timed
    t0 = time.time()
    test = scenario.SwellingTest(scenario=a.scenario, behaviour=a.behaviour, damage=a.damage, size_mm=(a.size_mm, a.size_mm),
                                 seed=a.seed, solver="adr", steps_per_decade=c["steps_per_decade"], tolerance=c["tolerance"],
                                 kelvin_units_per_decade=c["kelvin_units_per_decade"], t_end_days=a.t_end_days, out=a.run_dir)
    res = scenario.run(test)
    import yade
    sizes = {}
    for I in yade.Omega().interactions:  # Kelvin units of each kind's chain (per direction)
        if I.isReal and I.phys.kindName not in sizes:
            sizes[I.phys.kindName] = int(scene.scene_law().chainSize(I.phys.kind))
    timing["chain_size"] = sizes
    timing.update(total_s=time.time() - t0, status=res["status"], n_particles=res["n_particles"],
                  n_contacts_by_kind=res["n_contacts_by_kind"], config=c, threads=a.threads)
    with open(os.path.join(a.run_dir, "bench.json"), "w") as f:
        json.dump(timing, f, indent=1)
    print("BENCH_DONE", json.dumps(timing), flush=True)


# ------------------------------------------------------------------------------------------ driver
def run_one(a, scen, run_dir, c):
    if os.path.exists(os.path.join(run_dir, "bench.json")) and not a.force:
        return "cached"
    os.makedirs(run_dir, exist_ok=True)
    cmd = [LAUNCHER, "-n", "-j", str(a.threads), "-x", THIS, "--worker", "--scenario", scen, "--behaviour", a.behaviour,
           "--size-mm", str(a.size_mm), "--seed", str(a.seed), "--run-dir", run_dir, "--config", json.dumps(c)]
    if a.damage:
        cmd.append("--damage")
    if a.t_end_days:
        cmd += ["--t-end-days", str(a.t_end_days)]
    t0 = time.time()
    with open(os.path.join(run_dir, "run.log"), "w") as log:
        p = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, timeout=a.timeout)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed (exit {p.returncode}); see {run_dir}/run.log")
    return f"{time.time() - t0:.0f} s"


def final_values(res):
    eps = [(x + y) / 2 for x, y in zip(res["swelling_strain_x"], res["swelling_strain_y"])]
    q = {k: (res["per_kind"][k]["fn_p05_kN"][-1], res["per_kind"][k]["fn_p95_kN"][-1]) for k in paper.KIND_NAMES}
    return eps, q


def at_time(res, eps, t):
    """Strain at time t [day] (the run's step at t, which every run with 1..40 steps a decade has)."""
    times = res["times_days"]
    k = min(range(len(times)), key=lambda i: abs(math.log(times[i] / t)))
    return eps[k] if abs(math.log(times[k] / t)) < 1e-6 else float("nan")


def errors(res, ref):
    eps, q = final_values(res)
    eps_r, q_r = final_values(ref)
    e = {"strain": abs(eps[-1] - eps_r[-1]) / abs(eps_r[-1])}
    hist = [abs(eps[-1] - eps_r[-1]) / abs(eps_r[-1])]
    for t in (10.0, 100.0, 1000.0):
        if t < ref["times_days"][-1]:
            x, xr = at_time(res, eps, t), at_time(ref, eps_r, t)
            if math.isfinite(x) and math.isfinite(xr) and xr != 0:
                hist.append(abs(x - xr) / abs(xr))
    e["strain_history"] = max(hist)
    for k in paper.KIND_NAMES:
        scale = max(abs(q_r[k][0]), abs(q_r[k][1]))
        e[f"{k}_p05"] = abs(q[k][0] - q_r[k][0]) / scale if scale > 0 else 0.0
        e[f"{k}_p95"] = abs(q[k][1] - q_r[k][1]) / scale if scale > 0 else 0.0
    e["force_max"] = max(v for key, v in e.items() if key.endswith(("_p05", "_p95")))
    e["max"] = max(e["strain"], e["force_max"])
    if res.get("damage"):
        # broken contacts: difference of the kind's broken fraction, in percentage points; one point
        # weighs as 1 % in 'max' (a crack pattern has no natural relative error)
        for k in paper.KIND_NAMES:
            n, n_r = res["n_contacts_by_kind"][k], ref["n_contacts_by_kind"][k]
            if n and n_r:
                e[f"{k}_broken"] = abs(res["per_kind"][k]["broken"][-1] / n - ref["per_kind"][k]["broken"][-1] / n_r)
        e["broken_max"] = max((v for key, v in e.items() if key.endswith("_broken")), default=0.0)
        e["max"] = max(e["max"], e["broken_max"])
    return e


def sweep_rows(rows, sweep, f):
    """The rows of one factor's sweep, the base included, sorted by the factor's value."""
    base = DEFAULT if sweep == "default" else REFERENCE
    sel = [r for r in rows if (sweep, f) in r["member"] or r["config"] == base]
    return sorted(sel, key=lambda r: r["config"][f])


def candidates(rows, target):
    """Combinations of the factors' values, cheapest first, whose estimated error is within target:
    error = sum of each value's own error (reference sweep); cost = ADR iterations of the default x
    each value's iteration factor (default sweep). Iterations, not wall time: they are exact, and the
    wall time per iteration hardly depends on these settings (the Kelvin chain costs per step, not
    per iteration, so its factor is 1 and a shorter chain wins a tie)."""
    import itertools
    default = next(r for r in rows if r["config"] == DEFAULT)
    own, cost = {}, {}
    for f in FACTORS:
        own[f] = {r["config"][f]: r["errors"]["max"] for r in sweep_rows(rows, "reference", f)}
        cost[f] = {r["config"][f]: (1.0 if f == "kelvin_units_per_decade" else r["iterations"] / default["iterations"])
                   for r in sweep_rows(rows, "default", f)}
    values = [sorted(set(own[f]) & set(cost[f])) for f in FACTORS]
    out = []
    for combo in itertools.product(*values):
        c = dict(zip(FACTORS, combo))
        est = sum(own[f][c[f]] for f in FACTORS)
        if est <= target:
            it = default["iterations"] * math.prod(cost[f][c[f]] for f in FACTORS)
            out.append((it, est, c))
    return sorted(out, key=lambda t: (t[0], t[2]["kelvin_units_per_decade"]))


def fmt_e(x):
    return f"{100 * x:.2f}" if x < 0.1 else f"{100 * x:.1f}"


def load_row(run_dir, label, c):
    with open(os.path.join(run_dir, "results.json")) as f:
        res = json.load(f)
    with open(os.path.join(run_dir, "bench.json")) as f:
        b = json.load(f)
    return {"label": label, "config": c, "dir": run_dir, "res": res, "wall_s": b["solve_s"], "iterations": b["iterations"],
            "steps": b["steps"], "status": b["status"], "n_particles": b["n_particles"], "member": []}


def table(tag, rows):
    damage = any("broken_max" in r["errors"] for r in rows)
    head = ("| run | N | tol | Kelvin/dec | steps | ADR it | wall s | strain % | strain hist % | " +
            " | ".join(f"{k} p05 % | {k} p95 %" for k in paper.KIND_NAMES) +
            (" | broken M / I / A % | broken error (points) " if damage else "") + " | max % |")
    lines = [f"### {tag}", "", head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        c, e = r["config"], r["errors"]
        extra = ""
        if damage:
            extra = (" | " + " / ".join(f"{100 * r['final']['broken'][k]:.1f}" for k in paper.KIND_NAMES) +
                     f" | {100 * e.get('broken_max', 0):.1f}")
        lines.append(f"| {r['label']} | {c['steps_per_decade']:g} | {c['tolerance']:.0e} | {c['kelvin_units_per_decade']:g} | "
                     f"{r['steps']} | {r['iterations']} | {r['wall_s']:.1f} | {fmt_e(e['strain'])} | {fmt_e(e['strain_history'])} | " +
                     " | ".join(f"{fmt_e(e[k + '_p05'])} | {fmt_e(e[k + '_p95'])}" for k in paper.KIND_NAMES) + extra + f" | **{fmt_e(e['max'])}** |")
    return "\n".join(lines)


def plot(all_rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(all_rows)
    fig, axes = plt.subplots(1, len(names), figsize=(5.4 * len(names), 4.4), squeeze=False)
    style = {"steps_per_decade": ("o", "C0", "N"), "tolerance": ("s", "C1", "tol"), "kelvin_units_per_decade": ("^", "C2", "Kelvin")}
    X = "iterations"  # exact and proportional to the wall time (the measured wall times are noisy: see the tables)
    floor = 1e-4  # errors of 0 (the reference itself) are drawn at 0.01 %
    for ax, tag in zip(axes[0], names):
        rows = all_rows[tag]
        for sweep, ls in (("default", "-"), ("reference", ":")):
            for f, (m, col, lab) in style.items():
                sel = [r for r in sweep_rows(rows, sweep, f)]
                if len(sel) < 2:
                    continue
                ax.plot([r[X] for r in sel], [100 * max(r["errors"]["max"], floor) for r in sel], ls, marker=m, color=col,
                        ms=5, label=f"{lab} ({sweep} sweep)", mfc="none" if sweep == "reference" else col)
                for r in sel:
                    ax.annotate(f"{r['config'][f]:g}", (r[X], 100 * max(r["errors"]["max"], floor)), fontsize=6,
                                xytext=(3, 2), textcoords="offset points", color=col)
        for r in rows:
            if "recommended" in r["label"]:
                ax.plot([r[X]], [100 * max(r["errors"]["max"], floor)], "*", color="C3", ms=12)
                ax.annotate(r["label"].split("= ")[-1].replace("recommended ", "rec. "), (r[X], 100 * max(r["errors"]["max"], floor)),
                            fontsize=7, xytext=(4, -9), textcoords="offset points", color="C3")
        d = next(r for r in rows if r["config"] == DEFAULT)
        ax.plot([d[X]], [100 * d["errors"]["max"]], "kD", ms=7, label="default (10, 1e-4, 1)")
        for t in TARGETS:
            ax.axhline(100 * t, color="grey", lw=0.8, ls="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("ADR iterations of the whole run (cost; wall time ~ iterations)")
        ax.set_ylabel("largest error [%]: strain, Fn 5/95 % quantiles")
        ax.set_title(f"{tag}, {rows[0]['n_particles']} discs")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)


def driver(a):
    summary = {"size_mm": a.size_mm, "t_end_days": a.t_end_days, "seed": a.seed, "behaviour": a.behaviour, "damage": a.damage,
               "threads": a.threads, "reference": REFERENCE, "default": DEFAULT, "factors": FACTORS, "sweeps": a.sweeps,
               "load_before": os.getloadavg(), "scenarios": {}}
    all_rows = {}
    md = []
    for scen in a.scenarios:
        tag = scen + ("-dmg" if a.damage else "")
        rows, by_name, failed = [], {}, {}

        def get(label, c, member=None):
            name = config_name(c)
            if name in failed:
                return None
            if name not in by_name:
                run_dir = os.path.join(a.out, tag, name)
                try:
                    how = run_one(a, scen, run_dir, c)
                except (RuntimeError, subprocess.TimeoutExpired) as e:
                    # e.g. a tolerance the cracking run cannot reach within maxIterations: reported, not fatal
                    print(f"bench_accuracy: {tag} {label:<22} {name:<22} FAILED: {e}", flush=True)
                    failed[name] = {"label": label, "config": c, "error": str(e).splitlines()[0]}
                    return None
                print(f"bench_accuracy: {tag} {label:<22} {name:<22} {how}", flush=True)
                r = load_row(run_dir, label, c)
                by_name[name] = r
                rows.append(r)
            r = by_name[name]
            if member:
                r["member"].append(member)
            return r
        for label, sweep, f, c in configs(a.sweeps):
            get(label, c, (sweep, f) if sweep else None)
        for c in a.extra:
            get("extra", dict(DEFAULT, **json.loads(c)))
        ref = by_name[config_name(REFERENCE)]["res"]
        for r in rows:
            r["errors"] = errors(r["res"], ref)
        rec = {}
        if "reference" in a.sweeps and "default" in a.sweeps and a.verify:
            for t in TARGETS:
                rec[f"{t:g}"] = None
                rejected, n_try = set(), 0
                for cost, est, c in candidates(rows, t):
                    if (c["steps_per_decade"], c["tolerance"]) in rejected:
                        continue  # the chain length does not rescue a step count and tolerance that failed
                    if n_try >= a.verify:
                        break
                    n_try += 1
                    r = get(f"recommended {100 * t:g} %", c)
                    if r is None:
                        rejected.add((c["steps_per_decade"], c["tolerance"]))
                        continue
                    r["errors"] = errors(r["res"], ref)
                    if r["label"] != f"recommended {100 * t:g} %":
                        r["label"] += f" = recommended {100 * t:g} %"
                    r.setdefault("estimate", {"iterations": cost, "error": est})
                    if r["errors"]["max"] <= t:
                        rec[f"{t:g}"] = {"config": c, "wall_s": r["wall_s"], "iterations": r["iterations"], "error": r["errors"]["max"],
                                         "estimated_error": est, "estimated_iterations": cost, "tries": n_try}
                        break
                    r["label"] = r["label"].replace("recommended", "rejected")
                    rejected.add((c["steps_per_decade"], c["tolerance"]))
        for r in rows:
            eps, q = final_values(r["res"])
            r["final"] = {"strain": eps[-1], "quantiles_kN": q,
                          "broken": {k: r["res"]["per_kind"][k]["broken"][-1] / max(r["res"]["n_contacts_by_kind"][k], 1) for k in paper.KIND_NAMES}}
            del r["res"]
        all_rows[tag] = rows
        summary["scenarios"][tag] = {"rows": rows, "recommended": rec, "n_particles": rows[0]["n_particles"]}
        md.append(table(f"{tag} ({rows[0]['n_particles']} discs, {a.size_mm:g} x {a.size_mm:g} mm, {a.behaviour}, damage "
                        f"{'on' if a.damage else 'off'})", rows))
        md.append("")
        for name, f in failed.items():
            md.append(f"- {f['label']} ({name}) did not finish: {f['error']}")
        summary["scenarios"][tag]["failed"] = failed
        default_row = next(r for r in rows if r["config"] == DEFAULT)
        for t, r in rec.items():
            if r is None:
                md.append(f"- within {100 * float(t):g} %: no verified setting")
            else:
                c = r["config"]
                md.append(f"- within {100 * float(t):g} %: N {c['steps_per_decade']:g}, tolerance {c['tolerance']:.0e}, "
                          f"{c['kelvin_units_per_decade']:g} Kelvin units a decade: error {fmt_e(r['error'])} % "
                          f"(estimated {fmt_e(r['estimated_error'])} %), {r['iterations']} ADR iterations (estimated {r['estimated_iterations']:.0f}), "
                          f"wall {r['wall_s']:.1f} s; default: {fmt_e(default_row['errors']['max'])} %, {default_row['iterations']} iterations")
        md.append("")
    summary["load_after"] = os.getloadavg()
    text = "\n".join(md)
    print(text)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "accuracy.json"), "w") as f:
        json.dump(summary, f, indent=1, default=float)
    with open(os.path.join(a.out, "accuracy.md"), "w") as f:
        f.write(text + "\n")
    plot(all_rows, os.path.join(a.out, "accuracy.png"))
    print(f"wrote {a.out}/accuracy.json, accuracy.md, accuracy.png")


ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--scenarios", nargs="+", default=["isr", "asr-fine"])
ap.add_argument("--behaviour", default="viscoelastic", choices=("elastic", "viscoelastic"))
ap.add_argument("--damage", action="store_true", help="damage on (default off: the error is smooth without it); adds the "
                "broken fraction per kind, whose difference in percentage points counts as percent in 'max'")
ap.add_argument("--reference", default="", help='JSON changes to the reference settings, e.g. \'{"tolerance": 1e-5}\'')
ap.add_argument("--size-mm", type=float, default=20.0, help="side of the square specimen [mm]")
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--t-end-days", type=float, default=0.0, help="last time [day]; 0: the paper's (for quick trials)")
ap.add_argument("--threads", type=int, default=1, help="OpenMP threads of every run (-j)")
ap.add_argument("--sweeps", nargs="+", default=["default", "reference"], choices=("default", "reference"),
                help="vary each factor from the default, from the reference, or both")
ap.add_argument("--verify", type=int, default=6, help="recommended settings: run up to this many candidates per target")
ap.add_argument("--extra", action="append", default=[], help='a further configuration to run and tabulate, JSON changes '
                'from the default, e.g. {"steps_per_decade": 5, "tolerance": 1e-5}')
ap.add_argument("--timeout", type=float, default=3600, help="per run [s]")
ap.add_argument("--force", action="store_true", help="rerun configurations that have a bench.json")
ap.add_argument("--out", default=os.path.join(REPO, "out", "bench", "accuracy"))
ap.add_argument("--worker", action="store_true", help="internal: run one configuration in this YADE process")
ap.add_argument("--scenario", help="internal (worker)")
ap.add_argument("--run-dir", help="internal (worker)")
ap.add_argument("--config", help="internal (worker): JSON settings")
with options.refuse_bad("bench_accuracy.py"):  # every option before any run (NaN, infinity), exit 2
    args = ap.parse_args(sys.argv[1:])
    args.out = os.path.abspath(options.output_folder("out", args.out))
    for sc in args.scenarios:
        options.choice("scenarios", sc, tuple(paper.SCENARIOS))
    options.number("size_mm", args.size_mm, lo=0, unit="mm")
    options.integer("seed", args.seed, lo=0)
    if args.t_end_days != 0:
        options.number("t_end_days", args.t_end_days, lo=1, unit="day", allowed="0 (the paper's end) or 1 < t_end_days < inf [day]")
    options.integer("threads", args.threads, lo=1)
    options.integer("verify", args.verify, lo=0)
    options.number("timeout", args.timeout, lo=0, unit="s")
    if args.reference:
        try:
            changes = json.loads(args.reference)
        except json.JSONDecodeError as e:
            changes = None
            options.bad("reference", args.reference, f"a JSON object of {', '.join(REFERENCE)} ({e})")
        if not isinstance(changes, dict):
            options.bad("reference", args.reference, f"a JSON object of {', '.join(REFERENCE)}")
        for k, v in changes.items():
            options.choice("reference key", k, tuple(REFERENCE))
            options.number(f"reference {k}", v, lo=0)
        REFERENCE.update(changes)
    for text in args.extra:
        try:
            extra = json.loads(text)
        except json.JSONDecodeError as e:
            extra = None
            options.bad("extra", text, f"a JSON object of settings ({e})")
        if not isinstance(extra, dict):
            options.bad("extra", text, "a JSON object of settings")
        for k, v in extra.items():
            if not isinstance(v, str):
                options.number(f"extra {k}", v, lo=0)
if args.worker:
    worker(args)
else:
    driver(args)
