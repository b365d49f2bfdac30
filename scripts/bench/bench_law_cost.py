# SPDX-License-Identifier: GPL-2.0-or-later
"""Per-iteration cost of Law2_ScGeom_SwellPhys_AgingSwelling against YADE's
Law2_ScGeom_FrictPhys_CundallStrack on the same contacts, and the per-physical-step cost of the
contact kinds (set-up and commit of creep and swelling state) under AdrLogTimeIntegrator.

    /usr/bin/python3 scripts/bench/bench_law_cost.py [--n-discs 2000] [--threads 1 2] [--repeat 3]
        [--iters 2000] [--out out/bench/law_cost.json]
    (runs one worker per thread count: scripts/yade-swelldem -n -j N -x bench_law_cost.py --worker ...;
     the same command under scripts/yade-swelldem -n -x works too)

Part 1, per iteration (no integrator: positions never change, so every variant sees the same
geometry): a swelldem.meso assembly with radii scaled by --radius-scale (1.04: every contact of the
assembly overlaps, i.e. is in compression and goes through the whole of both laws), bonded contacts
created explicitly, the same kn = E_c A / L and ks = 0.3 kn in both laws (the plugin's uRef set to 0
so its forces equal CundallStrack's kn x overlap; checked). Variants: 'cundall' (stock law, friction
angle next to 90 degrees: the Coulomb check runs, never slips), 'elastic' (no swelling, no damage),
'viscoelastic', 'damage' (elastic, tensile cut-off on, nothing breaks: all compressed), 'swelling'
(elastic, d_inf > 0), 'all' (viscoelastic + damage + swelling). The time per iteration of the
InteractionLoop (O.timingEnabled, execTime) and the wall time of O.run are taken over
--repeat builds x --chunks chunks (the least disturbed chunk is the figure; medians in the JSON), the
variants interleaved so that load from other processes hits all of them.
Without the log-time integrator a kind runs one open-ended step, so the variants differ here only by
what Law2::go does every iteration.

Part 2, per physical step: the same scene with every disc fixed under
AdrLogTimeIntegrator(minIterations=1): each iteration is a whole physical step (every contact sets up
its step in the InteractionLoop, the integrator commits every contact), which isolates what creep and
swelling add per step; compared with part 1's 'elastic' iteration on the same scene.
Timings are wall clock on a shared 2-core machine: noisy; repeat and take medians.
"""
import argparse
import os
import sys
import time

THIS = next(os.path.abspath(c) for c in (sys.argv[0], globals().get("__file__"), "scripts/bench/bench_law_cost.py")
            if c and os.path.basename(c) == "bench_law_cost.py")
sys.path.insert(0, os.path.dirname(THIS))
import _common as C  # noqa: E402

VARIANTS = ("cundall", "elastic", "viscoelastic", "damage", "swelling", "all")
STEP_VARIANTS = ("elastic", "aging-elastic", "viscoelastic", "swelling", "viscoelastic+swelling")
TARGET_RATIO = 1.2

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--n-discs", type=int, default=2000)
ap.add_argument("--seed", type=int, default=1)
ap.add_argument("--radius-scale", type=float, default=1.04, help="radii x this: every assembly contact overlaps")
ap.add_argument("--iters", type=int, default=2000, help="timed iterations per variant and repeat")
ap.add_argument("--steps", type=int, default=200, help="timed physical steps per variant in part 2")
ap.add_argument("--repeat", type=int, default=3, help="scene builds per variant (interleaved)")
ap.add_argument("--chunks", type=int, default=10, help="timed chunks per build; the least disturbed chunk is reported")
ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
ap.add_argument("--out", default=os.path.join(C.REPO_DIR, "out", "bench", "law_cost.json"))
ap.add_argument("--worker", action="store_true", help="internal: measure in this YADE process, print JSON")
from swelldem import options, paper  # noqa: E402  (_common put py/ on the path)

with options.refuse_bad("bench_law_cost.py"):  # every option before any work (NaN, infinity), exit 2
    args = ap.parse_args(sys.argv[1:])
    options.output_file("out", args.out)
    options.integer("n_discs", args.n_discs, lo=2)
    options.integer("seed", args.seed, lo=0)
    options.number("radius_scale", args.radius_scale, lo=1, hi=1.5, lo_incl=True)
    for name in ("iters", "steps", "repeat", "chunks"):
        options.integer(name, getattr(args, name), lo=1)
    for t in args.threads:
        options.integer("threads", t, lo=1)


# ------------------------------------------------------------------------------------------ worker
def kinds_for(variant):
    from swelldem import dem
    beh = "viscoelastic" if variant in ("viscoelastic", "all", "viscoelastic+swelling") else \
        ("aging-elastic" if variant == "aging-elastic" else "elastic")
    swell = C.D_INF_PAPER_M if variant in ("swelling", "all", "viscoelastic+swelling") else 0.0
    dmg = variant in ("damage", "all")
    return {name: dem.contact_kind(name, behaviour=beh, young=E, shear_ratio=0.3, swell_disp_inf=swell, kinetics="isr", damage=dmg,
                                     tensile_strength=4e6) for name, E in YOUNG.items()}


YOUNG = dict(zip(paper.KIND_NAMES, (25e9, 15e9, paper.AGGREGATE_YOUNG)))
YOUNG_BY_ID = {paper.KIND_IDS[name]: E for name, E in YOUNG.items()}


def build(assembly, variant, integrator=None):
    if variant == "cundall":
        ids, inters = C.build_scene(assembly, "stock", integrator=integrator, radius_scale=args.radius_scale, fix_bottom=True,
                                    young_by_kind=YOUNG_BY_ID)
    else:
        ids, inters = C.build_scene(assembly, "swell", kinds_for(variant), integrator=integrator, radius_scale=args.radius_scale,
                                    fix_bottom=True)
        for I in inters:
            I.phys.uRef = 0.0  # stress-free at zero overlap, as CundallStrack
    return ids, inters


def iloop():
    import yade
    return next(e for e in yade.Omega().engines if e.__class__.__name__ == "InteractionLoop")


def time_chunks(n, chunks):
    """n iterations in `chunks` runs; per chunk (InteractionLoop us/iteration, wall us/iteration,
    integrator us/iteration or None)."""
    import yade
    O = yade.Omega()
    O.timingEnabled = True
    integ = [e for e in O.engines if e.__class__.__name__ == "AdrLogTimeIntegrator"]
    m = max(1, n // chunks)
    res = []
    for _ in range(chunks):
        for e in O.engines:
            e.execTime, e.execCount = 0, 0
        t0 = time.perf_counter()
        O.run(m, True)
        wall = time.perf_counter() - t0
        res.append((iloop().execTime / 1e3 / m, wall / m * 1e6, (integ[0].execTime / 1e3 / m if integ else None)))
    return res


def stats(xs):
    """min (the least disturbed chunk: the figure used for the ratios), median, all."""
    return {"min": min(xs), "median": C.median(xs), "all": xs}


def worker():
    import yade
    from yade import wrapper as W
    from swelldem.dem import scene_law
    O = yade.Omega()
    assembly = C.make_assembly(args.n_discs, seed=args.seed)
    out = {"threads": O.numThreads, "loadavg_start": os.getloadavg(), "n_discs": len(assembly.r), "n_contacts": len(assembly.contacts), "per_iteration": {},
           "per_step": {}, "checks": {}}
    samples = {v: {"iloop_us": [], "wall_us": []} for v in VARIANTS}
    forces = {}
    for rep in range(args.repeat):
        for v in VARIANTS:
            ids, inters = build(assembly, v)
            O.run(2, True)  # the contacts set up their step
            if v != "cundall":
                # aging kinds set kn from E(28 d): give every variant CundallStrack's stiffness (kept: the step does not change)
                for c, I in enumerate(inters):
                    kn = YOUNG_BY_ID[int(assembly.kind[c])] * float(assembly.facet_area_m2[c]) / float(assembly.distance_m[c])
                    I.phys.kn, I.phys.ks = kn, 0.3 * kn
            O.run(2, True)  # warm-up
            n_real = sum(1 for I in O.interactions if I.isReal)
            if rep == 0:
                forces[v] = [(I.phys.normalForce.norm(), I.phys.shearForce.norm()) for I in inters]
                out["checks"].setdefault("n_real", {})[v] = n_real
                out["checks"].setdefault("n_compressed", {})[v] = sum(1 for I in inters if I.geom.penetrationDepth > 0)
                if v != "cundall":
                    out["checks"].setdefault("broken", {})[v] = sum(1 for I in inters if I.phys.broken)
            for il, wall, _ in time_chunks(args.iters, args.chunks):
                samples[v]["iloop_us"].append(il)
                samples[v]["wall_us"].append(wall)
    ref = forces["cundall"]
    for v in VARIANTS:
        fmax = max(f[0] for f in ref)
        out["checks"].setdefault("max_force_diff_vs_cundall_rel", {})[v] = \
            max(max(abs(a[0] - b[0]), abs(a[1] - b[1])) for a, b in zip(forces[v], ref)) / fmax
        s = samples[v]
        out["per_iteration"][v] = {"iloop_us": stats(s["iloop_us"]), "wall_us": stats(s["wall_us"])}

    # Part 2: every iteration a physical step (all discs fixed, ADR with minIterations = 1).
    step_samples = {v: {"iloop_us": [], "adr_us": [], "wall_us": []} for v in STEP_VARIANTS}
    for rep in range(args.repeat):
        for v in STEP_VARIANTS:
            solver = W.AdrLogTimeIntegrator(tStart=1.0, tEnd=3650.0, stepsPerDecade=args.steps / 3.0, tolerance=1e-4, minIterations=1,
                                            verbose=False)
            ids, inters = build(assembly, v, integrator=solver)
            for i in ids:
                O.bodies[i].state.blockedDOFs = "xyzXYZ"
            O.run(3, True)  # initialisation, then two steps
            n = min(args.steps, solver.nSteps - 3)
            chunks = time_chunks(n, args.chunks)
            assert solver.step >= n, "part 2 expects one physical step per iteration"
            if rep == 0:
                out["checks"].setdefault("steps_timed", {})[v] = n
                out["checks"].setdefault("chain_size", {})[v] = scene_law().chainSize(inters[0].phys.kind)
            for il, wall, adr in chunks:
                step_samples[v]["iloop_us"].append(il)
                step_samples[v]["adr_us"].append(adr)
                step_samples[v]["wall_us"].append(wall)
    for v in STEP_VARIANTS:
        s = step_samples[v]
        out["per_step"][v] = {k: stats(s[k]) for k in s}
    out["loadavg_end"] = os.getloadavg()
    C.emit(out)


# ------------------------------------------------------------------------------------------ driver
def driver():
    runs = {}
    for j in args.threads:
        print(f"threads {j}: measuring ...", flush=True)
        runs[j] = C.run_worker(THIS, j, ["--n-discs", args.n_discs, "--seed", args.seed, "--radius-scale", args.radius_scale,
                                         "--iters", args.iters, "--steps", args.steps, "--repeat", args.repeat,
                                         "--chunks", args.chunks])
    first = runs[args.threads[0]]
    print("load average (1 min) at start/end of each worker: " +
          ", ".join(f"j={j}: {r['loadavg_start'][0]:.2f}/{r['loadavg_end'][0]:.2f}" for j, r in runs.items()))
    print(f"\nassembly: {first['n_discs']} discs, {first['n_contacts']} contacts, real interactions per variant "
          f"{first['checks']['n_real']}, compressed {first['checks']['n_compressed']['cundall']}")
    print("forces against CundallStrack (max relative difference): " +
          ", ".join(f"{v} {x:.1e}" for v, x in first["checks"]["max_force_diff_vs_cundall_rel"].items()))
    print("\nPart 1: InteractionLoop time per iteration [us] (least disturbed chunk) and ratio to CundallStrack")
    hdr = f"{'variant':>14}" + "".join(f" | {'j=' + str(j) + ' us':>9} | {'ratio':>6} | {'ns/contact':>10}" for j in args.threads)
    print(hdr)
    table = {}
    for v in VARIANTS:
        line = f"{v:>14}"
        for j in args.threads:
            r = runs[j]
            pi, pc = r["per_iteration"][v], r["per_iteration"]["cundall"]
            us = pi["iloop_us"]["min"]
            ratio = us / pc["iloop_us"]["min"]
            table.setdefault(v, {})[j] = {"iloop_us": us, "ratio_vs_cundall": ratio, "ns_per_contact": us * 1e3 / r["n_contacts"],
                                          "ratio_of_medians": pi["iloop_us"]["median"] / pc["iloop_us"]["median"],
                                          "wall_us": pi["wall_us"]["min"], "wall_ratio_vs_cundall": pi["wall_us"]["min"] / pc["wall_us"]["min"]}
            line += f" | {us:>9.1f} | {ratio:>6.2f} | {us * 1e3 / r['n_contacts']:>10.1f}"
        print(line)
    print(f"(target: elastic / cundall <= {TARGET_RATIO}; ratios of medians and wall-time ratios in the JSON)")
    print("ratio of medians: " + "; ".join(f"j={j}: " + ", ".join(f"{v} {table[v][j]['ratio_of_medians']:.2f}" for v in VARIANTS[1:])
                                           for j in args.threads))
    print("\nPart 2: one physical step per iteration (all discs fixed, ADR minIterations = 1) [us, least disturbed chunk]")
    print(f"{'kind':>22}" + "".join(f" | {'j=' + str(j) + ' loop':>10} | {'ADR':>7} | {'step extra':>10} | {'ns/contact':>10}"
                                    for j in args.threads))
    steps = {}
    for v in STEP_VARIANTS:
        line = f"{v:>22}"
        for j in args.threads:
            r = runs[j]
            s = {k: x["min"] for k, x in r["per_step"][v].items()}
            extra = s["iloop_us"] + s["adr_us"] - r["per_iteration"]["elastic"]["iloop_us"]["min"]
            steps.setdefault(v, {})[j] = {"iloop_us": s["iloop_us"], "adr_us": s["adr_us"], "extra_per_step_us": extra,
                                          "extra_ns_per_contact": extra * 1e3 / r["n_contacts"]}
            line += f" | {s['iloop_us']:>10.1f} | {s['adr_us']:>7.1f} | {extra:>10.1f} | {extra * 1e3 / r['n_contacts']:>10.1f}"
        print(line)
    print("(step extra = InteractionLoop + integrator time of a stepping iteration - InteractionLoop time of a plain 'elastic'\n"
          " iteration of part 1: what one physical step adds, once per step, on top of its ADR iterations)")
    C.write_json(args.out, {"args": vars(args), "target_ratio": TARGET_RATIO, "per_iteration": table, "per_step": steps,
                            "runs": {str(j): r for j, r in runs.items()}})


if args.worker:
    worker()
else:
    driver()
