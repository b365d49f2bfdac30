# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared helpers of the benchmarks: a bonded 2D assembly from swelldem.meso turned into a YADE scene
with either swelldem's law or YADE's Law2_ScGeom_FrictPhys_CundallStrack (bench_adr_vs_yade.py,
bench_law_cost.py), timing statistics, child processes (YADE workers, or plain Python for the
geometry benches) and JSON output. The YADE parts import yade lazily, so the module also loads in plain python3."""
import json
import math
import os
import statistics
import subprocess
import sys
import time

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
REPO_DIR = os.path.dirname(os.path.dirname(BENCH_DIR))
if os.path.join(REPO_DIR, "py") not in sys.path:
    sys.path.insert(0, os.path.join(REPO_DIR, "py"))
LAUNCHER = os.path.join(REPO_DIR, "scripts", "yade-swelldem")
from swelldem import paper  # noqa: E402

# Discs per mm^2 of swelldem.meso's default packing (997 discs on 25 x 25 mm, seed 1).
DISCS_PER_MM2 = 1.595
# Paper Table 3.2: d_inf = eps_inf x 2 R_mean = 1000e-6 x 2 x 0.397 mm.
D_INF_PAPER_M = paper.EPS_INF * 2 * paper.TABLE_3_2_R_MEAN


def side_mm_for(n_discs):
    """Side of the square specimen [mm] that holds about n_discs discs of the default grading."""
    return math.sqrt(n_discs / DISCS_PER_MM2)


def make_assembly(n_discs, seed=1, aggregate_fraction=0.35):
    """A square swelldem.meso assembly of about n_discs discs (SI arrays, see docs/mesostructure.md)."""
    from swelldem import meso
    s = side_mm_for(n_discs)
    return meso.generate(seed=seed, width_mm=s, height_mm=s, aggregate_area_fraction=aggregate_fraction)


def build_scene(a, law, kinds=None, integrator=None, extra_engines=(), radius_scale=1.0, fix_bottom=True,
                shear_ratio=0.3, young_by_kind=None, swell_mask=None):
    """Puts assembly `a` into the current YADE scene through swelldem.dem.build_scene (O.reset()
    first, O.tags kept) with explicit bonded contacts.

    law: 'swell' (ConcreteMat, Ip2_ConcreteMat_ConcreteMat_SwellPhys with `kinds` = dict MORTAR/ITZ/AGG ->
    ContactKind, Law2_ScGeom_SwellPhys_AgingSwelling) or 'stock' (FrictMat, Ip2_FrictMat_FrictMat_FrictPhys,
    Law2_ScGeom_FrictPhys_CundallStrack, friction angle next to 90 degrees: no slip, kn = E_c A / L and
    ks = shear_ratio kn set per contact from young_by_kind [Pa] so both laws see the same stiffness).
    The engine list is ForceResetter, InteractionLoop, extra_engines..., integrator (no collider: the
    contact set is the assembly's and stays so). radius_scale > 1 turns every contact into an overlap.
    fix_bottom: discs touching the bottom side are fixed (no rigid-body modes).
    swell_mask: per-contact booleans; where False the contact gets SwellPhys.swellDispInf = 0.
    Returns (ids of the bodies, list of the interactions in assembly order)."""
    import yade
    from swelldem import dem
    W = yade.wrapper
    if law == "swell":
        groups = sorted(set(int(v) for v in a.aggregate_id) - {-1})
        mats = [W.ConcreteMat(young=30e9, poisson=0.2, density=2400, aggregateId=-1, label="mortar")]
        mats += [W.ConcreteMat(young=60e9, poisson=0.2, density=2600, aggregateId=g) for g in groups]
        index = {g: k + 1 for k, g in enumerate(groups)}
        material_of = [index.get(int(g), 0) for g in a.aggregate_id]
        ip2 = dem.concrete_ip2(kinds)
        law2 = W.Law2_ScGeom_SwellPhys_AgingSwelling()
    elif law == "stock":
        mats, material_of = [W.FrictMat(young=30e9, poisson=0.2, density=2400, frictionAngle=math.pi / 2 - 1e-9)], None
        ip2 = W.Ip2_FrictMat_FrictMat_FrictPhys()
        law2 = W.Law2_ScGeom_FrictPhys_CundallStrack(neverErase=True)
    else:
        raise ValueError(f"build_scene: law = {law!r} is out of range; allowed: 'swell', 'stock'")
    ybottom = float(min(a.y - a.r))
    fixed = [k for k in range(len(a.r)) if fix_bottom and (a.y[k] - a.r[k]) <= ybottom + 1e-3 * a.r[k]]
    # Detection factor wide enough for the assembly's near-contacts (gap <= 0.05 Rmax).
    gap = max(0.0, float((a.gap_m / (a.r[a.contacts[:, 0]] + a.r[a.contacts[:, 1]])).max()))
    ig2 = W.Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=1.0 + 2 * gap + 1e-6)
    ids, inters = dem.build_scene(a.x, a.y, a.r * radius_scale, mats, ip2, law2, integrator, material_of=material_of,
                                  contacts=a.contacts, fixed=fixed, ig2=ig2, collider=False, extra_engines=extra_engines)
    for c, I in enumerate(inters):
        if law == "swell":
            I.phys.area = float(a.facet_area_m2[c])
            if swell_mask is not None and not swell_mask[c]:
                I.phys.swellDispInf = 0.0
        else:
            L = float(a.distance_m[c])
            kn = young_by_kind[int(a.kind[c])] * float(a.facet_area_m2[c]) / L
            I.phys.kn, I.phys.ks = kn, shear_ratio * kn
    return ids.tolist(), inters


def positions(ids):
    import yade
    O = yade.Omega()
    return [(O.bodies[i].state.pos[0], O.bodies[i].state.pos[1]) for i in ids]


def free_mask(ids):
    import yade
    O = yade.Omega()
    return [O.bodies[i].dynamic for i in ids]


def median(xs):
    return statistics.median(xs) if xs else float("nan")


def spread(xs):
    """(min, median, max) of a list."""
    return (min(xs), statistics.median(xs), max(xs)) if xs else (float("nan"),) * 3


def fit_power(xs, ys):
    """Exponent b and prefactor of y = p x^b (least squares in log-log)."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((x - mx) ** 2 for x in lx)
    b = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx if sxx > 0 else float("nan")
    return b, math.exp(my - b * mx)


def write_json(path, data):
    d = os.path.dirname(os.path.abspath(path))
    os.makedirs(d, exist_ok=True)
    with open(path, "w") as f:
        json.dump(data, f, indent=1)
    print(f"wrote {path}")


def run_plain_child(script, args):
    """Runs `script args...` with this Python (no YADE), one process a measurement so that its peak
    memory is its own; returns the JSON of the last line it prints. A child that fails raises
    RuntimeError with the last line of its stderr (e.g. the generator's refusal)."""
    p = subprocess.run([sys.executable, script] + [str(x) for x in args], capture_output=True, text=True)
    if p.returncode != 0:
        err = p.stderr.strip().splitlines()
        raise RuntimeError(err[-1] if err else f"{script} exited with {p.returncode}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def run_worker(script, threads, args, timeout=3600):
    """Runs `script --worker args...` under scripts/yade-swelldem with `threads` OpenMP threads; returns
    the JSON it prints on its last line that starts with 'BENCH_JSON '."""
    cmd = [LAUNCHER, "-n", "-j", str(threads), "-x", script, "--worker"] + [str(x) for x in args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("BENCH_JSON ")]
    if p.returncode != 0 or not lines:
        sys.stderr.write(p.stdout[-4000:] + p.stderr[-4000:])
        raise RuntimeError(f"{' '.join(cmd)} failed (exit {p.returncode})")
    return json.loads(lines[-1][len("BENCH_JSON "):])


def run_result(cmd):
    """Runs a child that prints its result as one line `RESULT {json}` (bench_implicit_damage.py);
    returns (that dict, the process's wall time [s]). A child without the line raises RuntimeError
    with the command and the last line of its stderr."""
    t = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t
    lines = [ln for ln in p.stdout.splitlines() if ln.startswith("RESULT ")]
    if not lines:
        raise RuntimeError(f"{' '.join(cmd)} failed: {(p.stderr.strip().splitlines() or ['?'])[-1]}")
    return json.loads(lines[-1][len("RESULT "):]), wall


def emit(data):
    """The worker's answer to run_worker."""
    print("BENCH_JSON " + json.dumps(data), flush=True)


def in_yade():
    try:
        import yade  # noqa: F401
        return hasattr(yade, "Omega")
    except ImportError:
        return False
