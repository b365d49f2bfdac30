# SPDX-License-Identifier: GPL-2.0-or-later
"""The gel pockets of ASR with reactive coarse aggregate: which contacts swell, under each reading
of the paper's text (swelldem.paper.GEL_POCKET_READINGS), and how large their forces can be.

Plain numpy/scipy on an Assembly (no YADE): the scenario draws the pockets with choose(), the YADE
scene gets them through swelldem.dem.set_gel_pockets, and restrained_forces() gives the force
balance's bound before any run.

Why a bound: a gel pocket is a contact whose stress-free length grows by d; the rest of the
specimen can only give way, so a pocket's compression is at most the force of a fully restrained
one, kn d = E_c A / L x d, reached when its two particles cannot move apart at all. The compression
tail of the aggregate contacts is the pockets' (the other aggregate contacts are squeezed by them,
not swollen), so the 5 % quantile of the AGG forces is bounded by the 5 % quantile of {-kn d on the
pockets, 0 elsewhere}: a reading whose bound stays above a table's value cannot reach it, whatever
the packing does.
"""
import numpy as np

from ..paper import GEL_DISPLACEMENT_READINGS, GEL_POCKET_READINGS
from .assembly import AGG, ITZ
from .generator import choose_contacts

READINGS = tuple(GEL_POCKET_READINGS)
DISPLACEMENTS = tuple(GEL_DISPLACEMENT_READINGS)


def _check(name, value, allowed):
    if value not in allowed:
        raise ValueError(f"swelldem.meso.gel_pockets: {name} = {value!r} is out of range; allowed: {', '.join(allowed)}")


def midpoints(assembly):
    """(m, dim) contact midpoints [m]: halfway between the two particle centres."""
    pos = np.column_stack([assembly.x, assembly.y] + ([assembly.z] if assembly.dim == 3 else []))
    c = assembly.contacts
    return 0.5 * (pos[c[:, 0]] + pos[c[:, 1]])


def rim_contacts(assembly):
    """The AGG contacts of an aggregate's outer particle layer: at least one of the two particles
    also has an ITZ contact (sorted indices)."""
    c = assembly.contacts
    at_rim = np.zeros(assembly.n_particles, dtype=bool)
    itz = assembly.kind == ITZ
    at_rim[c[itz, 0]] = True
    at_rim[c[itz, 1]] = True
    agg = assembly.kind == AGG
    return np.nonzero(agg & (at_rim[c[:, 0]] | at_rim[c[:, 1]]))[0]


def pool_kinds(reading):
    """The kind ids the pockets of a reading are drawn from, "the coarse aggregates contacts": AGG,
    and ITZ for 'with-itz'."""
    return (AGG, ITZ) if reading == "with-itz" else (AGG,)


def pool(assembly, reading):
    """The contacts (sorted indices) of the kinds the pockets of a reading are drawn from."""
    return np.nonzero(np.isin(assembly.kind, pool_kinds(reading)))[0]


def count(assembly, reading, fraction):
    """How many contacts swell: round(fraction x the contacts of pool(assembly, reading))."""
    return int(round(float(fraction) * len(pool(assembly, reading))))


def choose(assembly, reading, fraction, seed, radius_m=1e-3):
    """The gel-pocket contacts (sorted indices) of one reading: 'single', 'clustered', 'rim' or
    'with-itz' (swelldem.paper.GEL_POCKET_READINGS), count(assembly, reading, fraction) of them,
    drawn with numpy's generator of SeedSequence(seed). 'single' is
    choose_contacts(assembly, AGG, fraction, seed). 'clustered': a centre is drawn among the AGG
    contacts not chosen yet, and the AGG contacts of the same aggregate whose midpoints lie within
    radius_m [m] of its midpoint join, nearest first, until the count is reached. ValueError for a
    reading, fraction or radius out of range, or a rim holding fewer contacts than the count."""
    _check("reading", reading, READINGS)
    if not 0.0 <= float(fraction) <= 1.0:
        raise ValueError(f"swelldem.meso.gel_pockets: fraction = {fraction} is out of range; allowed: [0, 1]")
    if reading == "single":
        return choose_contacts(assembly, AGG, fraction, seed)
    k = count(assembly, reading, fraction)
    rng = np.random.default_rng(np.random.SeedSequence(int(seed)))
    if reading == "with-itz":
        drawn_from = pool(assembly, reading)
        return np.sort(rng.choice(drawn_from, size=k, replace=False)) if k else np.zeros(0, dtype=np.int64)
    if reading == "rim":
        rim = rim_contacts(assembly)
        if k > len(rim):
            raise ValueError(f"swelldem.meso.gel_pockets: gel_fraction = {fraction} is out of range for gel_pockets 'rim': the "
                             f"aggregates' rims of this mesostructure hold {len(rim)} AGG contacts, fewer than its {k} gel pockets; "
                             f"allowed: gel_fraction <= {len(rim) / max(1, (assembly.kind == AGG).sum()):.3f}")
        return np.sort(rng.choice(rim, size=k, replace=False)) if k else np.zeros(0, dtype=np.int64)
    if not (np.isfinite(radius_m) and radius_m > 0):
        raise ValueError(f"swelldem.meso.gel_pockets: radius_m = {radius_m} is out of range; allowed: 0 < radius_m < inf [m]")
    from scipy.spatial import cKDTree
    agg = assembly.contacts_of_kind(AGG)
    mid = midpoints(assembly)[agg]
    agg_of = assembly.aggregate_id[assembly.contacts[agg, 0]]
    tree = cKDTree(mid)
    taken = np.zeros(len(agg), dtype=bool)
    chosen = []
    while len(chosen) < k:
        free = np.nonzero(~taken)[0]
        centre = int(rng.choice(free))
        near = np.asarray(tree.query_ball_point(mid[centre], radius_m), dtype=np.int64)
        near = near[(agg_of[near] == agg_of[centre]) & ~taken[near]]
        near = near[np.argsort(np.linalg.norm(mid[near] - mid[centre], axis=1), kind="stable")]
        near = near[: k - len(chosen)]
        taken[near] = True
        chosen.extend(near.tolist())
    return np.sort(agg[np.asarray(chosen, dtype=np.int64)]) if k else np.zeros(0, dtype=np.int64)


def pocket_displacement(d_rule_m, displacement, fraction):
    """The pockets' ultimate swelling displacement [m]: 'rule' keeps Table 3.2's d = eps_inf x 2 R_mean
    (d_rule_m), 'aggregate' divides it by the gel fraction (swelldem.paper.GEL_DISPLACEMENT_READINGS)."""
    _check("displacement", displacement, DISPLACEMENTS)
    if displacement == "rule":
        return float(d_rule_m)
    if not float(fraction) > 0:
        raise ValueError(f"swelldem.meso.gel_pockets: fraction = {fraction} is out of range for displacement 'aggregate'; "
                         "allowed: 0 < fraction <= 1")
    return float(d_rule_m) / float(fraction)


def restrained_forces(assembly, chosen, d_m, young_of_kind):
    """Each pocket's fully restrained force [N], -E_c A / L x d_m (compression negative), with E_c
    [Pa] the modulus of its kind (young_of_kind: {kind id: E_c}), in the order of `chosen`."""
    chosen = np.asarray(chosen, dtype=np.int64)
    e = np.array([young_of_kind[int(k)] for k in assembly.kind[chosen]], dtype=float)
    return -e * assembly.facet_area_m2[chosen] / assembly.distance_m[chosen] * float(d_m)


def quantile_bound(assembly, chosen, restrained, kind=AGG, q=0.05):
    """The force balance's bound on the q quantile [N] of the `kind` contacts' normal forces: the
    quantile of {the restrained force on the pockets of that kind, 0 on its other contacts}."""
    chosen = np.asarray(chosen, dtype=np.int64)
    sel = assembly.kind[chosen] == kind
    f = np.zeros(int((assembly.kind == kind).sum()))
    f[: int(sel.sum())] = np.asarray(restrained)[sel]
    return float(np.quantile(f, q)) if f.size else float("nan")
