# SPDX-License-Identifier: GPL-2.0-or-later
"""Cost of one ADR iteration against the disc count, and whether the numbering of discs and contacts
matters (issue 13). Three numberings of one mesostructure (same discs, same contacts, only renumbered):
"packing" (swelldem.meso.generate(order="packing"): the packing's order of placement, in layers from
the bottom; contacts in the Laguerre diagram's order, sorted by their first disc), "hilbert"
(generate's default: discs along a Hilbert curve, contacts sorted by their discs) and "random" (a
control made here: discs in a random order, contacts sorted by their first disc). A
benchmark, not a timed test.

    /usr/bin/python3 scripts/bench/bench_order.py [--sizes-mm 25 50 80 110 160] [--orders packing hilbert random]
        [--repeats 2] [--rounds 4] [--behaviour elastic] [--damage] [--out out/bench/order.json]

One YADE process (-j 1) per (size, repeat) holds one scene per numbering (O.addScene; the order in
which they are built rotates with the repeat, since the heap's history differs), each the
swelling test's (ISR, seed 1, paper-micro parameters; elastic contacts and damage off by default, as in
issue 13; ADR at 10 steps a decade, its default tolerance, collider every 20 iterations), built by
swelldem.scenario.build as scripts/bench/bench_scaling.py builds it, then run for 21 iterations (set-up,
warm-up). The scenes then take turns (--rounds rounds, the order of turns reversed every round), each
turn a window of about 1.5e6 / discs ADR iterations of physical step 1, so that the numberings see the
same drift of a shared machine. Time: the process's CPU time (time.process_time, not disturbed by other
jobs taking the core) per iteration and disc, fastest turn of each scene; the engines' share from YADE's
O.timingEnabled (execTime, wall clock) of that turn. Table: median over the --repeats processes, and the
spread (max / min over the processes); for each numbering, the ratio of the cost per disc at the largest
size over the smallest (1 = linear in the disc count).
"""
import argparse
import dataclasses
import os
import statistics
import sys
import time

THIS = next(os.path.abspath(c) for c in (sys.argv[0], globals().get("__file__"), "scripts/bench/bench_order.py")
            if c and os.path.basename(c) == "bench_order.py")
sys.path.insert(0, os.path.dirname(THIS))
import _common as C  # noqa: E402
from swelldem import options  # noqa: E402  (_common put py/ on the path)

ORDERS = ("packing", "hilbert", "random")


# ------------------------------------------------------------------------------------- numberings
def random_permutation(n, seed=0):
    """New disc k = old disc perm[k]: the control numbering."""
    import numpy as np
    return np.random.default_rng(seed).permutation(n)


def renumbered(a, perm):
    """Assembly `a` with its discs renumbered (new k = old perm[k]) and its contacts and Laguerre
    neighbours sorted by their new (i < j): the same values, only permuted."""
    import numpy as np
    new = np.empty(len(perm), dtype=np.int64)
    new[perm] = np.arange(len(perm))
    ch = {k: getattr(a, k)[perm] for k in ("x", "y", "r", "material", "aggregate_id", "cell_area_m2")}
    for pairs, along in (("contacts", ("kind", "facet_length_m", "facet_area_m2", "distance_m", "gap_m", "facet_segment_m")),
                         ("neighbours", ("neighbour_facet_length_m",))):
        ij = new[getattr(a, pairs).astype(np.int64)]
        lo, hi = ij.min(axis=1), ij.max(axis=1)
        q = np.lexsort((hi, lo))
        ch[pairs] = np.stack([lo[q], hi[q]], axis=1).astype(getattr(a, pairs).dtype)
        ch.update({k: getattr(a, k)[q] for k in along})
    return dataclasses.replace(a, **ch)


def locality(a):
    """Mean and median |i - j| over the contacts (numbers of discs)."""
    import numpy as np
    d = np.abs(a.contacts[:, 0].astype(np.int64) - a.contacts[:, 1])
    return {"mean_abs_i_minus_j": float(d.mean()), "median_abs_i_minus_j": float(np.median(d))}


# ------------------------------------------------------------------------------------------ worker
def worker(a):
    import tempfile
    import yade
    from swelldem import meso, scenario
    O = yade.Omega()
    # the swelling test's scene and solver (scenario.build; nothing is written: out is only checked)
    test = scenario.SwellingTest(scenario="isr", behaviour=a.behaviour, damage=a.damage, size_mm=(a.size_mm, a.size_mm),
                                 seed=a.seed, solver="adr", solver_params={"verbose": False}, out=tempfile.gettempdir())
    base = meso.generate(seed=test.seed, width_mm=a.size_mm, height_mm=a.size_mm, order="packing")
    out = {"size_mm": a.size_mm, "n_particles": base.n_particles, "n_contacts": base.n_contacts, "load_start": os.getloadavg(),
           "orders": {}}
    scenes, solvers = {}, {}
    build = a.orders[a.repeat % len(a.orders):] + a.orders[:a.repeat % len(a.orders)]  # build order rotated over the repeats
    out["build_order"] = build
    for order in build:
        if order == "random":
            asm = renumbered(base, random_permutation(base.n_particles))
        else:
            asm = base if order == "packing" else meso.generate(seed=test.seed, width_mm=a.size_mm, height_mm=a.size_mm, order=order)
        k = O.addScene()
        O.switchToScene(k)
        # one solver a scene (build() prepares it and the kinds anew)
        solvers[order] = scenario.build(test, assembly=asm, reset=False).solver
        O.run(21, True)  # set-up and warm-up (the collider's first runs)
        scenes[order] = k
        out["orders"][order] = dict(locality(asm), turns=[])
    n_it = max(20, int(1.5e6 / base.n_particles))
    for rnd in range(a.rounds):
        for order in (a.orders if rnd % 2 == 0 else list(reversed(a.orders))):
            O.switchToScene(scenes[order])
            for e in O.engines:
                e.execTime, e.execCount = 0, 0
            O.timingEnabled = True
            it0 = solvers[order].totalIterations
            c0 = time.process_time()
            O.run(n_it, True)
            cpu = time.process_time() - c0
            O.timingEnabled = False
            n = max(solvers[order].totalIterations - it0, 1)
            turn = {("collider" if e.label == "collider" else e.__class__.__name__): e.execTime / n / base.n_particles for e in O.engines}
            turn["cpu"] = cpu / n / base.n_particles * 1e9
            out["orders"][order]["turns"].append(turn)
    for order in a.orders:
        o = out["orders"][order]
        o["best"] = min(o["turns"], key=lambda t: t["cpu"])  # ns per iteration and disc
        O.switchToScene(scenes[order])
        o["unbalanced_end"] = float(solvers[order].unbalanced)  # the same problem: equal but for round-off
        o["iterations_end"] = int(solvers[order].totalIterations)
    out["load_end"] = os.getloadavg()
    C.emit(out)


# ------------------------------------------------------------------------------------------ driver
def driver(a):
    runs = []
    t_start = time.time()
    for rep in range(a.repeats):
        for s in a.sizes_mm:
            args = ["--size-mm", s, "--repeat", rep, "--seed", a.seed, "--rounds", a.rounds, "--behaviour", a.behaviour, "--orders"] + list(a.orders) + \
                (["--damage"] if a.damage else [])
            r = C.run_worker(THIS, 1, args, timeout=a.timeout)
            r["repeat"] = rep
            runs.append(r)
            print(f"bench_order: repeat {rep}, {s:g} mm, {r['n_particles']} discs, ns per iteration and disc: " +
                  ", ".join(f"{o} {r['orders'][o]['best']['cpu']:.0f}" for o in a.orders) + f" (load {r['load_start'][0]:.1f})", flush=True)
    table = []
    for s in a.sizes_mm:
        rs = [r for r in runs if r["size_mm"] == s]
        for o in a.orders:
            best = [r["orders"][o]["best"] for r in rs]
            med = {k: statistics.median(b[k] for b in best) for k in best[0]}
            cpus = [b["cpu"] for b in best]
            table.append({"size_mm": s, "order": o, "n_particles": rs[0]["n_particles"], "n_contacts": rs[0]["n_contacts"],
                          "ns_per_disc": med, "spread": max(cpus) / min(cpus),
                          "mean_abs_i_minus_j": rs[0]["orders"][o]["mean_abs_i_minus_j"],
                          "median_abs_i_minus_j": rs[0]["orders"][o]["median_abs_i_minus_j"],
                          "unbalanced_end": [r["orders"][o]["unbalanced_end"] for r in rs]})
    lines = [f"bench_order: {a.behaviour}, damage {'on' if a.damage else 'off'}, -j 1; CPU time per ADR iteration and disc, "
             f"fastest of {a.rounds} turns, median of {a.repeats} processes; {time.time() - t_start:.0f} s", "",
             "| size mm | discs | numbering | abs(i-j) mean / median | CPU ns/disc | x packing | ms/iteration | "
             "InteractionLoop ns/disc | integrator ns/disc | collider ns/disc | spread |", "|" + "---|" * 11]
    for t in table:
        p = t["ns_per_disc"]
        ref = next(u for u in table if u["size_mm"] == t["size_mm"] and u["order"] == a.orders[0])["ns_per_disc"]["cpu"]
        lines.append(f"| {t['size_mm']:g} | {t['n_particles']} | {t['order']} | {t['mean_abs_i_minus_j']:.0f} / "
                     f"{t['median_abs_i_minus_j']:.0f} | {p['cpu']:.0f} | {p['cpu'] / ref:.2f} | {p['cpu'] * t['n_particles'] / 1e6:.2f} | "
                     f"{p.get('InteractionLoop', 0):.0f} | {p.get('AdrLogTimeIntegrator', 0):.0f} | {p.get('collider', 0):.1f} | "
                     f"{t['spread']:.2f} |")
    summary = {}
    lines.append("")
    for o in a.orders:
        ts = sorted([t for t in table if t["order"] == o], key=lambda t: t["n_particles"])
        lo, hi = ts[0], ts[-1]
        ratio = {k: hi["ns_per_disc"][k] / lo["ns_per_disc"][k] for k in ("cpu", "InteractionLoop", "AdrLogTimeIntegrator")}
        b = C.fit_power([t["n_particles"] for t in ts], [t["ns_per_disc"]["cpu"] * t["n_particles"] for t in ts])[0] \
            if len(ts) > 1 else float("nan")
        summary[o] = {"ratio_per_disc": ratio, "exponent": b}
        lines.append(f"{o}: cost per disc at {hi['n_particles']} discs / at {lo['n_particles']} discs: CPU {ratio['cpu']:.2f} "
                     f"(InteractionLoop {ratio['InteractionLoop']:.2f}, integrator {ratio['AdrLogTimeIntegrator']:.2f}); "
                     f"cost per iteration ~ N^{b:.2f}")
    text = "\n".join(lines)
    print(text)
    C.write_json(a.out, {"runs": runs, "table": table, "summary": summary, "args": vars(a), "table_md": text})


ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--sizes-mm", type=float, nargs="+", default=[25, 50, 80, 110, 160])
ap.add_argument("--orders", nargs="+", default=list(ORDERS), choices=ORDERS, help="numberings; the first is the reference")
ap.add_argument("--repeats", type=int, default=2, help="processes per size")
ap.add_argument("--rounds", type=int, default=4, help="timed turns per numbering in a process (the fastest is kept)")
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--behaviour", default="elastic", choices=("elastic", "viscoelastic"))
ap.add_argument("--damage", action="store_true")
ap.add_argument("--timeout", type=float, default=3600)
ap.add_argument("--out", default=os.path.join(C.REPO_DIR, "out", "bench", "order.json"))
ap.add_argument("--worker", action="store_true", help="internal: measure one size in this YADE process")
ap.add_argument("--size-mm", type=float, help="internal (worker)")
ap.add_argument("--repeat", type=int, default=0, help="internal (worker): rotates the order in which the scenes are built")
args = ap.parse_args(sys.argv[1:])
if args.worker:
    worker(args)
else:
    with options.refuse_bad("bench_order.py"):  # exit status 2, as argparse's, before any work
        args.out = os.path.abspath(options.output_file("out", args.out))
    driver(args)
