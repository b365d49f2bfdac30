# SPDX-License-Identifier: GPL-2.0-or-later
"""Scaling of the swelling test with particle count and OpenMP threads (issue 7): wall time per ADR
iteration (split into InteractionLoop, collider, integrator), peak memory, and ADR iterations per
physical step of the first steps, for square specimens of about 1k to 40k discs. A benchmark, not a
timed test.

    /usr/bin/python3 scripts/bench/bench_scaling.py [--sizes-mm 25 50 80 110 160] [--threads 1 2]
        [--iters 400] [--steps 3] [--max-step-iters 4000] [--out out/bench/scaling.json]

One YADE process per (size, threads): scripts/yade-swelldem -n -j T -x this --worker ... The scene is
the swelling test's (swelldem.scenario: mesostructure of seed 1, ISR, viscoelastic contacts, damage
on unless --no-damage, paper-micro parameters, AdrLogTimeIntegrator at 10 steps a decade and
its default tolerance, collider every 20 iterations), built by swelldem.scenario.build as
scenario.run builds it, without the per-step recording. Measured:
- per iteration: the first --iters ADR iterations of physical step 1 with O.timingEnabled (engine
  execTime / iterations; 'wall' = O.run's wall time / iterations, which includes YADE's loop);
- ADR iterations of each of the first --steps physical steps (run to convergence after the timed
  window; the timing of this part is reported too), a step stopping at --max-step-iters is marked;
- peak memory: VmHWM of the YADE process after generation, after the scene is built and at the end
  (/proc/self/status), and the scene's bodies and interactions.
The driver prints the tables, a fit of time and iterations against the particle count, and an
EXTRAPOLATED whole-run time: per-iteration time x (ADR iterations of a whole run of a smaller
specimen, --calibration results.json, scaled by the growth of the first steps' iterations).
"""
import argparse
import json
import os
import sys
import time

THIS = next(os.path.abspath(c) for c in (sys.argv[0], globals().get("__file__"), "scripts/bench/bench_scaling.py")
            if c and os.path.basename(c) == "bench_scaling.py")
sys.path.insert(0, os.path.dirname(THIS))
import _common as C  # noqa: E402


def vm(field="VmHWM"):
    """A memory line of /proc/self/status [MB]."""
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


# ------------------------------------------------------------------------------------------ worker
def worker(a):
    import tempfile
    import yade
    from swelldem import scenario
    O = yade.Omega()
    out = {"size_mm": a.size_mm, "threads": O.numThreads, "damage": not a.no_damage, "load_start": os.getloadavg()}
    t0 = time.time()
    # the swelling test's scene and solver, as scenario.run builds them (nothing is written: out is only checked)
    test = scenario.SwellingTest(scenario="isr", behaviour=a.behaviour, damage=not a.no_damage, size_mm=(a.size_mm, a.size_mm), seed=a.seed,
                                 solver="adr", solver_params={"verbose": False}, out=tempfile.gettempdir())
    prepared = scenario.prepare(test)
    assembly = scenario.make_assembly(test)
    out["generate_s"] = time.time() - t0
    out["mem_after_generate_MB"] = vm()
    t1 = time.time()
    solver = scenario.build(test, prepared, assembly=assembly).solver
    out["build_s"] = time.time() - t1
    out["mem_after_build_MB"] = vm()
    out["n_particles"] = len(O.bodies)
    out["n_contacts"] = sum(1 for i in O.interactions if i.isReal)
    O.run(1, True)  # the integrator's initialisation (times, kinds, Kelvin chains)
    # Timed window: the first a.iters ADR iterations of physical step 1.
    for e in O.engines:
        e.execTime, e.execCount = 0, 0
    O.timingEnabled = True
    it0 = solver.totalIterations
    tw = time.time()
    O.run(a.iters, True)
    wall = time.time() - tw
    n = solver.totalIterations - it0
    O.timingEnabled = False
    per = {}
    for e in O.engines:
        name = "collider" if e.label == "collider" else e.__class__.__name__
        per[name] = e.execTime / 1e3 / max(n, 1)
    out["timed_iterations"] = n
    out["timed_step"] = solver.step
    out["per_iteration_us"] = per
    out["per_iteration_wall_us"] = wall / max(n, 1) * 1e6
    # The first a.steps physical steps to convergence (iteration counts).
    tr = time.time()
    stopped = False
    while len(solver.stepIterations) < a.steps and not solver.finished:
        if solver.iterInStep >= a.max_step_iters:
            stopped = True
            break
        O.run(min(200, a.max_step_iters - solver.iterInStep + 1), True)
    out["steps_wall_s"] = time.time() - tr + wall
    out["step_iterations"] = [int(v) for v in solver.stepIterations]
    out["step_unbalanced"] = [float(v) for v in solver.stepUnbalanced]
    out["unfinished_step"] = {"step": solver.step, "iterations": solver.iterInStep, "unbalanced": solver.unbalanced} if stopped else None
    out["total_iterations"] = int(solver.totalIterations)
    out["broken"] = sum(1 for i in O.interactions if i.isReal and i.phys.broken)
    out["mem_peak_MB"] = vm()
    out["mem_rss_end_MB"] = vm("VmRSS")
    out["load_end"] = os.getloadavg()
    C.emit(out)


# ------------------------------------------------------------------------------------------ driver
def plot(runs, threads, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(14, 4.2))
    for j, m in zip(threads, ("o-", "s--")):
        rs = sorted([r for r in runs if r["threads"] == j], key=lambda r: r["n_particles"])
        if not rs:
            continue
        n = [r["n_particles"] for r in rs]
        ax[0].plot(n, [r["per_iteration_wall_us"] / 1e3 for r in rs], m, label=f"-j {j}: wall")
        ax[0].plot(n, [r["per_iteration_us"].get("InteractionLoop", 0) / 1e3 for r in rs], m, alpha=0.5, label=f"-j {j}: InteractionLoop")
        ax[0].plot(n, [r["per_iteration_us"].get("AdrLogTimeIntegrator", 0) / 1e3 for r in rs], m, alpha=0.5, label=f"-j {j}: integrator")
        ax[1].plot(n, [r["mem_peak_MB"] for r in rs], m, label=f"-j {j}")
        if j == threads[0]:
            ax[2].plot(n, [sum(r["step_iterations"]) / max(len(r["step_iterations"]), 1) for r in rs], m, label="mean of the first steps")
    ax[0].set(xscale="log", yscale="log", xlabel="discs", ylabel="ms per ADR iteration", title="time per iteration")
    ax[1].set(xscale="log", yscale="log", xlabel="discs", ylabel="peak memory VmHWM [MB]", title="peak memory")
    ax[2].set(xscale="log", yscale="log", xlabel="discs", ylabel="ADR iterations per step", title="iterations per step (first steps)")
    for x in ax:
        x.grid(True, which="both", alpha=0.3)
        x.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)


def driver(a):
    runs = []
    old = {}
    if os.path.exists(a.out) and a.keep:
        with open(a.out) as f:
            for r in json.load(f).get("runs", []):
                old[(r["size_mm"], r["threads"])] = r
    for s in a.sizes_mm:
        for j in a.threads:
            if (s, j) in old:
                runs.append(old[(s, j)])
                print(f"bench_scaling: {s:g} mm, -j {j}: kept from {a.out}", flush=True)
                continue
            t0 = time.time()
            args = ["--size-mm", s, "--seed", a.seed, "--iters", a.iters, "--steps", a.steps, "--max-step-iters", a.max_step_iters,
                    "--behaviour", a.behaviour] + (["--no-damage"] if a.no_damage else [])
            r = C.run_worker(THIS, j, args, timeout=a.timeout)
            r["process_s"] = time.time() - t0
            runs.append(r)
            print(f"bench_scaling: {s:g} mm, -j {j}: {r['n_particles']} discs, {r['per_iteration_wall_us'] / 1e3:.2f} ms/iteration, "
                  f"peak {r['mem_peak_MB']:.0f} MB, first steps {r['step_iterations']}, {r['process_s']:.0f} s", flush=True)
            C.write_json(a.out, {"runs": runs, "args": vars(a)})
    # Tables.
    lines = ["| size mm | discs | contacts | -j | wall ms/it | InteractionLoop | collider | integrator | ForceResetter | "
             "peak MB | MB after build | first steps' iterations |", "|" + "---|" * 12]
    for r in sorted(runs, key=lambda r: (r["n_particles"], r["threads"])):
        p = r["per_iteration_us"]
        its = ", ".join(str(v) for v in r["step_iterations"]) + (f", ({r['unfinished_step']['iterations']}+)" if r["unfinished_step"] else "")
        lines.append(f"| {r['size_mm']:g} | {r['n_particles']} | {r['n_contacts']} | {r['threads']} | {r['per_iteration_wall_us'] / 1e3:.2f} | "
                     f"{p.get('InteractionLoop', 0) / 1e3:.2f} | {p.get('collider', 0) / 1e3:.3f} | {p.get('AdrLogTimeIntegrator', 0) / 1e3:.2f} | "
                     f"{p.get('ForceResetter', 0) / 1e3:.3f} | {r['mem_peak_MB']:.0f} | {r['mem_after_build_MB']:.0f} | {its} |")
    # Threads: speed-up per size.
    speed = []
    for s in a.sizes_mm:
        by = {r["threads"]: r for r in runs if r["size_mm"] == s}
        if 1 in by and 2 in by:
            speed.append({"size_mm": s, "n_particles": by[1]["n_particles"],
                          "wall": by[1]["per_iteration_wall_us"] / by[2]["per_iteration_wall_us"],
                          "InteractionLoop": by[1]["per_iteration_us"]["InteractionLoop"] / by[2]["per_iteration_us"]["InteractionLoop"],
                          "integrator": by[1]["per_iteration_us"]["AdrLogTimeIntegrator"] / by[2]["per_iteration_us"]["AdrLogTimeIntegrator"]})
    if speed:
        lines += ["", "| discs | speed-up -j 2 vs -j 1: wall | InteractionLoop | integrator |", "|---|---|---|---|"]
        lines += [f"| {s['n_particles']} | {s['wall']:.2f} | {s['InteractionLoop']:.2f} | {s['integrator']:.2f} |" for s in speed]
    # Fits and the extrapolation (1 thread, or the first thread count).
    j0 = a.threads[0]
    rs = sorted([r for r in runs if r["threads"] == j0], key=lambda r: r["n_particles"])
    fits, extra = {}, []
    if len(rs) >= 2:
        n = [r["n_particles"] for r in rs]
        fits["time_per_iteration"] = C.fit_power(n, [r["per_iteration_wall_us"] for r in rs])
        fits["iterations_per_step"] = C.fit_power(n, [sum(r["step_iterations"]) / len(r["step_iterations"]) for r in rs if r["step_iterations"]])
        fits["peak_memory"] = C.fit_power(n, [r["mem_peak_MB"] for r in rs])
        lines += ["", f"Power fits over the sizes (-j {j0}): time per iteration ~ N^{fits['time_per_iteration'][0]:.2f}, "
                  f"iterations per step (first steps) ~ N^{fits['iterations_per_step'][0]:.2f}, peak memory ~ N^{fits['peak_memory'][0]:.2f}"]
    if a.calibration and os.path.exists(a.calibration) and rs:
        from swelldem.report import load_results
        cal = load_results(a.calibration)  # a run of any version, read in today's form
        n_cal = cal["n_particles"]
        first_cal = [int(v) for v in cal.get("iterations_per_step", [])[:a.steps]]
        log = os.path.dirname(os.path.abspath(a.calibration)) + ".log"
        if not any(first_cal) and os.path.exists(log):  # runs made before the per-step counts were recorded: their progress lines
            import re
            with open(log) as f:
                first_cal = [int(m.group(1)) for m in re.finditer(r"step \d+/\d+ .*?ADR iterations (\d+) ", f.read())][:a.steps]
        lines += ["", f"EXTRAPOLATED whole-run time (ISR, 36 steps, -j {j0}): ADR iterations of the whole run of {a.calibration} "
                  f"({n_cal} discs: {cal['iterations']} iterations; first {a.steps} steps {first_cal}) x (first steps' iterations at N / "
                  f"at {n_cal} discs) x time per iteration at N. Not measured.", "",
                  "| discs | iterations (extrapolated) | time per iteration ms | whole run (extrapolated) |", "|---|---|---|---|"]
        for r in rs:
            if not r["step_iterations"]:
                continue
            k = min(len(first_cal), len(r["step_iterations"]))
            growth = sum(r["step_iterations"][:k]) / sum(first_cal[:k])
            it = cal["iterations"] * growth
            t = it * r["per_iteration_wall_us"] / 1e6
            extra.append({"n_particles": r["n_particles"], "iterations": it, "wall_s": t})
            lines.append(f"| {r['n_particles']} | {it:.0f} | {r['per_iteration_wall_us'] / 1e3:.2f} | {t / 60:.1f} min |")
    text = "\n".join(lines)
    print(text)
    C.write_json(a.out, {"runs": runs, "speedup": speed, "fits": fits, "extrapolated": extra, "args": vars(a), "table_md": text})
    png = os.path.splitext(a.out)[0] + ".png"
    plot(runs, a.threads, png)
    print(f"wrote {png}")


ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--sizes-mm", type=float, nargs="+", default=[25, 50, 80, 110, 160])
ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--behaviour", default="viscoelastic", choices=("elastic", "viscoelastic"))
ap.add_argument("--no-damage", action="store_true")
ap.add_argument("--iters", type=int, default=400, help="timed ADR iterations (start of physical step 1)")
ap.add_argument("--steps", type=int, default=3, help="first physical steps run to convergence for their iteration counts")
ap.add_argument("--max-step-iters", type=int, default=4000, help="stop a step's count here (marked in the table)")
ap.add_argument("--calibration", default=os.path.join(C.REPO_DIR, "out", "paper40", "isr-ve-dmg", "results.json"),
                help="results.json of a whole run (same scenario) for the extrapolation")
ap.add_argument("--keep", action="store_true", help="reuse the (size, threads) runs already in --out")
ap.add_argument("--timeout", type=float, default=3600)
ap.add_argument("--out", default=os.path.join(C.REPO_DIR, "out", "bench", "scaling.json"))
ap.add_argument("--worker", action="store_true", help="internal: measure one (size, threads) in this YADE process")
ap.add_argument("--size-mm", type=float, help="internal (worker)")
from swelldem import options  # noqa: E402  (_common put py/ on the path)

with options.refuse_bad("bench_scaling.py"):  # every option before any work (NaN, infinity), exit 2
    args = ap.parse_args(sys.argv[1:])
    options.output_file("out", args.out)
    options.numbers("sizes_mm", args.sizes_mm, lo=0, unit="mm")
    for t in args.threads:
        options.integer("threads", t, lo=1)
    options.integer("seed", args.seed, lo=0)
    for name in ("iters", "steps", "max_step_iters"):
        options.integer(name, getattr(args, name), lo=1)
    options.number("timeout", args.timeout, lo=0, unit="s")
    if args.size_mm is not None:
        options.number("size_mm", args.size_mm, lo=0, unit="mm")
if args.worker:
    worker(args)
else:
    args.out = os.path.abspath(args.out)
    driver(args)
