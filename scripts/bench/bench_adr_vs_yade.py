# SPDX-License-Identifier: GPL-2.0-or-later
"""Iterations to static equilibrium: swelldem's AdrLogTimeIntegrator against YADE's own quasi-static
recipe (NewtonIntegrator(damping=0.4) + density scaling + GlobalStiffnessTimeStepper), same problem.

    scripts/yade-swelldem -n -j 1 -x scripts/bench/bench_adr_vs_yade.py [--n-discs 1000] [--seed 1]
        [--tolerances 1e-2 1e-3 1e-4 1e-5] [--check-every 10] [--out out/bench/adr_vs_yade.json]
    (/usr/bin/python3 scripts/bench/bench_adr_vs_yade.py ... relaunches itself under yade-swelldem)

Problem: a swelldem.meso concrete assembly (aggregates by default; --aggregate-fraction 0 with
--swell half gives mortar with a random half of the contacts swelling), bonded elastic contacts
(MORTAR 25 GPa, ITZ 15 GPa, AGG 60 GPa contact moduli, ks = 0.3 kn), discs on the bottom side fixed.
One physical step of ISR swelling (tau_c = 50 d, tau_L = 100 d) from 28 to 280 days: the mortar
contacts (or the chosen half) swell by d_inf (xi(280) - xi(28)), d_inf = 0.794e-6 m, the rest do not,
so the equilibrium carries internal forces.

(a) AdrLogTimeIntegrator(tStart=28, tEnd=280, stepsPerDecade=1), its own tolerance set out of reach
    (1e-12) so that it iterates until this script stops it;
(b) the same scene under NewtonIntegrator(damping=0.4, densityScaling=True) and
    GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.8, densityScaling=True); after one
    iteration (the contacts set themselves up, no load) each contact's kn, ks, duOffsetN, duOffsetS
    are overwritten with (a)'s values of the step.
Both are judged by the same measure, yade.utils.unbalancedForce(), evaluated by a PyRunner placed
after the InteractionLoop and before the integrator every --check-every iterations (so it sees the
forces of the current positions). "Iterations" = position updates since the load was applied,
counted at the first check below each tolerance (resolution: --check-every). The ADR's own ratio
(SwellPhys offsets count in its denominator) is recorded alongside, one iteration late.
Positions are compared, at each tolerance, between (a) and (b) and against a tight ADR reference
(--ref-tol). Timings are wall clock on a shared machine: noisy.
"""
import argparse
import math
import os
import sys
import time

# Under `yade -x`, __file__ is YADE's launcher and sys.argv[0] this script.
THIS = next(os.path.abspath(c) for c in (sys.argv[0], globals().get("__file__"), "scripts/bench/bench_adr_vs_yade.py")
            if c and os.path.basename(c) == "bench_adr_vs_yade.py")
sys.path.insert(0, os.path.dirname(THIS))
import _common as C  # noqa: E402

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--n-discs", type=int, default=1000, help="about this many discs (500-2000 intended)")
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--aggregate-fraction", type=float, default=0.35, help="coarse aggregate area fraction (0: mortar only)")
ap.add_argument("--swell", choices=("mortar", "half"), default="mortar",
                help="which contacts swell: the MORTAR kind, or a random half of all contacts")
ap.add_argument("--tolerances", type=float, nargs="+", default=[1e-2, 1e-3, 1e-4, 1e-5])
ap.add_argument("--ref-tol", type=float, default=1e-8, help="unbalancedForce of the ADR reference solution")
ap.add_argument("--err-targets", type=float, nargs="+", default=[1e-1, 1e-2, 1e-3, 1e-4],
                help="position errors (max over discs, relative to the largest displacement) to report iterations for")
ap.add_argument("--check-every", type=int, default=10, help="iterations between two unbalancedForce() checks")
ap.add_argument("--max-iter", type=int, default=400000, help="iterations at most per solver")
ap.add_argument("--damping", type=float, default=0.4, help="NewtonIntegrator.damping")
ap.add_argument("--safety", type=float, default=0.8, help="GlobalStiffnessTimeStepper.timestepSafetyCoefficient")
ap.add_argument("--gsts-interval", type=int, default=1, help="GlobalStiffnessTimeStepper.timeStepUpdateInterval (YADE default 1)")
ap.add_argument("--repeat", type=int, default=3, help="solve both this many times; timings are medians")
ap.add_argument("--threads", type=int, default=1, help="only when started from plain python3: -j of the relaunch")
ap.add_argument("--out", default=os.path.join(C.REPO_DIR, "out", "bench", "adr_vs_yade.json"))
from swelldem import options, paper  # noqa: E402  (_common put py/ on the path)

with options.refuse_bad("bench_adr_vs_yade.py"):  # every option before any work (NaN, infinity), exit 2
    args = ap.parse_args(sys.argv[1:])
    options.output_file("out", args.out)
    options.integer("n_discs", args.n_discs, lo=2)
    options.integer("seed", args.seed, lo=0)
    options.number("aggregate_fraction", args.aggregate_fraction, lo=0, hi=1, lo_incl=True)
    # loose tolerances are what this benchmark measures: range checked, no warning
    options.numbers("tolerances", args.tolerances, lo=0, hi=1)
    options.number("ref_tol", args.ref_tol, lo=0, hi=1)
    options.numbers("err_targets", args.err_targets, lo=0)
    options.integer("check_every", args.check_every, lo=1)
    options.integer("max_iter", args.max_iter, lo=1)
    options.number("damping", args.damping, lo=0, hi=1, lo_incl=True)
    options.number("safety", args.safety, lo=0, hi=1, hi_incl=True)
    options.integer("gsts_interval", args.gsts_interval, lo=1)
    options.integer("repeat", args.repeat, lo=1)
    options.integer("threads", args.threads, lo=1)

if not C.in_yade():  # plain python3: relaunch under YADE with the plugin
    os.execv(C.LAUNCHER, [C.LAUNCHER, "-n", "-j", str(args.threads), "-x", THIS] + sys.argv[1:])

import random  # noqa: E402

import yade  # noqa: E402
from yade import utils  # noqa: E402
from swelldem import dem  # noqa: E402

W = yade.wrapper
O = yade.Omega()
TOLS = sorted(set(args.tolerances), reverse=True)

assembly = C.make_assembly(args.n_discs, seed=args.seed, aggregate_fraction=args.aggregate_fraction)
n_c = len(assembly.contacts)
rng = random.Random(args.seed)
if args.swell == "half":
    swell_mask = [rng.random() < 0.5 for _ in range(n_c)]
else:
    swell_mask = [int(k) == paper.MORTAR for k in assembly.kind]
YOUNG = dict(zip(paper.KIND_NAMES, (25e9, 15e9, paper.AGGREGATE_YOUNG)))


def kinds():
    # Every kind carries d_inf; the per-contact mask (SwellPhys.swellDispInf = 0) decides who swells.
    return {name: dem.contact_kind(name, behaviour="elastic", young=E, shear_ratio=0.3, swell_disp_inf=C.D_INF_PAPER_M,
                                     kinetics="isr") for name, E in YOUNG.items()}


# Discs with a single contact (those that touched a specimen side in the packing: there is no wall
# here) can roll about it at no energy: their equilibrium position is not unique, so position
# comparisons leave them out.
n_contacts_of = [0] * len(assembly.r)
for i, j in assembly.contacts:
    n_contacts_of[int(i)] += 1
    n_contacts_of[int(j)] += 1


class Probe:
    """The PyRunner's state: unbalancedForce history, first crossing of each tolerance, and (given a
    reference solution) the position error at every check and the first crossing of each error target."""

    def __init__(self, tols, ref=None):
        self.tols, self.ref = list(tols), ref
        self.err_targets = list(args.err_targets) if ref is not None else []
        self.hist, self.cross, self.pos_at, self.adr_cross, self.err_cross = [], {}, {}, {}, {}
        self.done = False

    def __call__(self):
        it = O.iter - 1  # position updates since the load (applied at iteration 1 for both solvers)
        if it < 0 or self.done:
            return
        uf = utils.unbalancedForce()
        is_adr = isinstance(solver, W.AdrLogTimeIntegrator)
        adr = solver.unbalanced if is_adr else None
        row = [it, uf, adr, solver.damping if is_adr else None]
        if self.ref is not None:
            e = maxdiff(C.positions(ids), self.ref) / disp_scale
            row.append(e)
            for t in self.err_targets:
                if t not in self.err_cross and e <= t:
                    self.err_cross[t] = it
        self.hist.append(row)
        for t in self.tols:
            if t not in self.cross and uf <= t:
                self.cross[t] = it
                self.pos_at[t] = C.positions(ids)
            if adr is not None and t not in self.adr_cross and 0 < adr <= t:
                self.adr_cross[t] = it - 1  # solver.unbalanced is the previous iteration's
        finished = all(t in self.cross for t in self.tols) and all(t in self.err_cross for t in self.err_targets)
        if finished or it >= args.max_iter or not math.isfinite(uf):
            self.done = True
            O.stopAtIter = O.iter + 1


SOLVER_ENGINES = ("ForceResetter", "InteractionLoop", "AdrLogTimeIntegrator", "GlobalStiffnessTimeStepper", "NewtonIntegrator")


def engine_us(iters):
    return {e.__class__.__name__: e.execTime / 1e3 / max(iters, 1) for e in O.engines}


def solve(probe):
    sys.modules["__main__"].probe = probe
    for e in O.engines:
        e.execTime, e.execCount = 0, 0
    O.timingEnabled = True
    t0 = time.perf_counter()
    O.run()
    O.wait()
    return time.perf_counter() - t0


def run_adr(tols, ref=None):
    """(a): returns (probe, interactions, engine us/iteration, wall [s], iterations)."""
    global solver, ids
    solver = W.AdrLogTimeIntegrator(tStart=28.0, tEnd=280.0, stepsPerDecade=1, tolerance=1e-12, maxIterations=10 ** 9,
                                    verbose=False, label="solver")
    runner = W.PyRunner(command="probe()", iterPeriod=args.check_every)
    ids, inters = C.build_scene(assembly, "swell", kinds(), integrator=solver, extra_engines=[runner], swell_mask=swell_mask)
    probe = Probe(tols, ref)
    wall = solve(probe)
    if solver.finished and not probe.done:
        print(f"note: the ADR committed its step on its own (round-off criterion) at ADR iteration {solver.iterInStep}")
    assert all(I.phys.stepSerial == dem.scene_law().stepSerial for I in inters), "the step changed during the run"
    return probe, inters, engine_us(O.iter), wall, O.iter


def run_newton(step_data, ref):
    """(b): same, with (a)'s step data copied into the contacts after their set-up iteration."""
    global solver, ids
    solver = W.NewtonIntegrator(damping=args.damping, label="newton")
    gsts = W.GlobalStiffnessTimeStepper(timestepSafetyCoefficient=args.safety, densityScaling=True,
                                        timeStepUpdateInterval=args.gsts_interval, label="gsts")
    runner = W.PyRunner(command="probe()", iterPeriod=args.check_every)
    ids, inters = C.build_scene(assembly, "swell", kinds(), integrator=solver, extra_engines=[runner, gsts], swell_mask=swell_mask)
    solver.densityScaling = True  # a property that needs the timestepper in O.engines
    p_before = C.positions(ids)
    sys.modules["__main__"].probe = lambda: None
    O.step()  # the contacts set up their (open-ended, load-free) step; nothing moves
    moved = max(abs(p[k] - q[k]) for p, q in zip(C.positions(ids), p_before) for k in (0, 1))
    for I, (kn, ks, du, dus) in zip(inters, step_data):
        I.phys.kn, I.phys.ks, I.phys.duOffsetN, I.phys.duOffsetS = kn, ks, du, dus
    probe = Probe(TOLS, ref)
    wall = solve(probe)
    assert all(I.phys.stepSerial == dem.scene_law().stepSerial for I in inters)
    assert all(I.phys.kn == d[0] and I.phys.duOffsetN == d[2] for I, d in zip(inters, step_data)), "step data were reset"
    return probe, inters, engine_us(O.iter - 1), wall, O.iter - 1, moved


def maxdiff(p, q, mask=None):
    return max(math.hypot(a[0] - b[0], a[1] - b[1]) for a, b, f in zip(p, q, mask or compared) if f)


def rmsdiff(p, q):
    d = [(a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 for a, b, f in zip(p, q, compared) if f]
    return math.sqrt(sum(d) / len(d))


def timing_summary(runs):
    """Medians over the repeats of the wall and engine times per iteration [us]."""
    per = [sum(v for k, v in r[2].items() if k in SOLVER_ENGINES) for r in runs]
    return {"wall_us_per_iter": C.median([r[3] / r[4] * 1e6 for r in runs]), "wall_us_per_iter_all": [r[3] / r[4] * 1e6 for r in runs],
            "engine_us_per_iter": {k: C.median([r[2][k] for r in runs]) for k in runs[0][2]},
            "solver_us_per_iter": C.median(per), "solver_us_per_iter_all": per}


# Reference: the ADR to --ref-tol; it also gives the step data and the tolerance crossings of (a).
probe_a, inters, _, _, _ = run_adr(TOLS + [args.ref_tol])
pos0 = [(float(x), float(y)) for x, y in zip(assembly.x, assembly.y)]
free = C.free_mask(ids)
compared = [f and n >= 2 for f, n in zip(free, n_contacts_of)]
step_data = [(I.phys.kn, I.phys.ks, I.phys.duOffsetN, I.phys.duOffsetS) for I in inters]
fn_a = [I.phys.Fn for I in inters]
n_swelling = sum(1 for d in step_data if d[2] != 0)
ref = probe_a.pos_at.get(args.ref_tol) or C.positions(ids)
disp_scale = maxdiff(ref, pos0)

runs_a, runs_b = [], []
for rep in range(args.repeat):
    runs_a.append(run_adr(TOLS, ref))
    runs_b.append(run_newton(step_data, ref))
    print(f"repeat {rep + 1}/{args.repeat}: ADR {runs_a[-1][4]} iterations {runs_a[-1][3]:.2f} s, "
          f"Newton {runs_b[-1][4]} iterations {runs_b[-1][3]:.2f} s", flush=True)
pa, pb = runs_a[0][0], runs_b[0][0]
if any(r[0].cross != pa.cross for r in runs_a) or any(r[0].cross != pb.cross for r in runs_b):
    print("note: iteration counts differ between repeats (with threads > 1 the force summation order varies)")
results = {"adr": {"cross": pa.cross, "adr_own_ratio_cross": pa.adr_cross, "err_cross": pa.err_cross, "iterations_run": runs_a[0][4],
                   "history": pa.hist, "ref_reached": args.ref_tol in probe_a.cross, **timing_summary(runs_a)},
           "newton": {"cross": pb.cross, "err_cross": pb.err_cross, "iterations_run": runs_b[0][4], "history": pb.hist, "dt": O.dt,
                      "moved_in_setup_iteration_m": runs_b[0][5], **timing_summary(runs_b)}}
us_a, us_b = results["adr"]["solver_us_per_iter"], results["newton"]["solver_us_per_iter"]

rows, err_rows = [], []
for t in TOLS:
    ia, ib = pa.cross.get(t), pb.cross.get(t)
    row = {"tol": t, "adr_iter": ia, "newton_iter": ib, "ratio": (ib / ia) if ia and ib else None,
           "adr_own_ratio_iter": pa.adr_cross.get(t)}
    if ia is not None and ib is not None:
        row["pos_diff_a_b_m"] = maxdiff(pa.pos_at[t], pb.pos_at[t])
        row["adr_solver_ms"], row["newton_solver_ms"] = ia * us_a / 1e3, ib * us_b / 1e3
        row["time_ratio"] = row["newton_solver_ms"] / row["adr_solver_ms"]
    if ia is not None:
        row["adr_err_vs_ref_m"] = maxdiff(pa.pos_at[t], ref)
        row["adr_rms_err_vs_ref_m"] = rmsdiff(pa.pos_at[t], ref)
    if ib is not None:
        row["newton_err_vs_ref_m"] = maxdiff(pb.pos_at[t], ref)
        row["newton_rms_err_vs_ref_m"] = rmsdiff(pb.pos_at[t], ref)
    rows.append(row)
for e in sorted(args.err_targets, reverse=True):
    ia, ib = pa.err_cross.get(e), pb.err_cross.get(e)
    err_rows.append({"err": e, "adr_iter": ia, "newton_iter": ib, "ratio": (ib / ia) if ia and ib else None,
                     "time_ratio": (ib * us_b) / (ia * us_a) if ia and ib else None})

fn_abs = [abs(f) for f in fn_a]
single = [f and n < 2 for f, n in zip(free, n_contacts_of)]
summary = {
    "n_discs": len(ids), "n_free": sum(free), "n_contacts": n_c, "n_swelling_contacts": n_swelling,
    "contacts_by_kind": {k: sum(1 for v in assembly.kind if int(v) == i) for i, k in enumerate(paper.KIND_NAMES)},
    "swell": args.swell, "aggregate_fraction": args.aggregate_fraction, "seed": args.seed, "young_Pa": YOUNG,
    "duOffsetN_max_m": max(d[2] for d in step_data), "check_every": args.check_every, "threads": O.numThreads,
    "ref_tol": args.ref_tol, "max_displacement_m": disp_scale, "compared_discs": sum(compared),
    "ref_Fn_N": {"min": min(fn_a), "max": max(fn_a), "mean_abs": sum(fn_abs) / len(fn_abs),
                 "tension": sum(1 for f in fn_a if f > 0), "compression": sum(1 for f in fn_a if f < 0)},
    "loadavg_end": os.getloadavg(), "damping": args.damping, "safety": args.safety, "gsts_interval": args.gsts_interval, "repeat": args.repeat,
    "n_single_contact_discs": sum(single),
    "single_contact_pos_diff_a_b_m": maxdiff(pa.pos_at[TOLS[-1]], pb.pos_at[TOLS[-1]], single)
    if any(single) and TOLS[-1] in pa.cross and TOLS[-1] in pb.cross else None,
}
print(f"\nassembly: {len(ids)} discs ({sum(free)} free), {n_c} contacts {summary['contacts_by_kind']}, "
      f"{n_swelling} swelling by {summary['duOffsetN_max_m']:.3e} m; threads {O.numThreads}")
print(f"reference (ADR to unbalancedForce {args.ref_tol:g}): largest displacement u = {disp_scale:.3e} m, "
      f"Fn {min(fn_a):.3g} .. {max(fn_a):.3g} N, {summary['ref_Fn_N']['tension']} in tension, "
      f"{summary['ref_Fn_N']['compression']} in compression; positions compared on {sum(compared)} discs "
      f"({sum(single)} free discs with one contact left out)")


def fmt(v, f):
    return format(v, f) if v is not None else "-"


def rel(r, key):
    v = r.get(key)
    return format(v / disp_scale, ".2e") if v is not None else "-"


print(f"\n{'tolerance':>9} | {'ADR it':>7} | {'Newton it':>9} | {'it ratio':>8} | {'ADR own':>7} | {'ADR ms':>7} | "
      f"{'Newton ms':>9} | {'t ratio':>7} | {'|xa-xb|/u':>9} | {'ADR err/u':>9} | {'Newt err/u':>10} | {'ADR rms/u':>9} | {'Newt rms/u':>10}")
for r in rows:
    print(f"{r['tol']:>9.0e} | {fmt(r['adr_iter'], 'd'):>7} | {fmt(r['newton_iter'], 'd'):>9} | {fmt(r['ratio'], '.2f'):>8} | "
          f"{fmt(r['adr_own_ratio_iter'], 'd'):>7} | {fmt(r.get('adr_solver_ms'), '.0f'):>7} | {fmt(r.get('newton_solver_ms'), '.0f'):>9} | "
          f"{fmt(r.get('time_ratio'), '.2f'):>7} | {rel(r, 'pos_diff_a_b_m'):>9} | {rel(r, 'adr_err_vs_ref_m'):>9} | "
          f"{rel(r, 'newton_err_vs_ref_m'):>10} | {rel(r, 'adr_rms_err_vs_ref_m'):>9} | {rel(r, 'newton_rms_err_vs_ref_m'):>10}")
print(f"(it = position updates until unbalancedForce() <= tolerance, resolution {args.check_every}; ADR own = the same for the "
      "ADR's own ratio; ms = it x median solver-engine time per iteration; err = max, rms = root mean square over the discs of "
      "the distance to the reference; u = largest displacement of the reference)")
print(f"\n{'error/u':>9} | {'ADR it':>7} | {'Newton it':>9} | {'it ratio':>8} | {'t ratio':>7}")
for r in err_rows:
    print(f"{r['err']:>9.0e} | {fmt(r['adr_iter'], 'd'):>7} | {fmt(r['newton_iter'], 'd'):>9} | {fmt(r['ratio'], '.2f'):>8} | "
          f"{fmt(r['time_ratio'], '.2f'):>7}")
print("(iterations until the largest position error against the reference is below error x u)\n")
for key, res in results.items():
    eng = ", ".join(f"{k} {v:.1f}" for k, v in res["engine_us_per_iter"].items())
    print(f"{key:>6}: median wall {res['wall_us_per_iter']:.1f} us/iteration, solver engines {res['solver_us_per_iter']:.1f} "
          f"us/iteration (median of {args.repeat}; engines: {eng})")
dmp = [h[3] for h in pa.hist if h[3] is not None]
if dmp:
    q = sorted(dmp)
    print(f"ADR damping c dt over the checks: min {q[0]:.3g}, median {q[len(q) // 2]:.3g}, max {q[-1]:.3g} "
          f"(last {dmp[-1]:.3g}; clamp maxDamping {W.AdrLogTimeIntegrator().maxDamping:g})")
    summary["adr_damping_c_dt"] = {"min": q[0], "median": q[len(q) // 2], "max": q[-1], "last": dmp[-1]}
C.write_json(args.out, {"summary": summary, "rows": rows, "err_rows": err_rows, "runs": results})
