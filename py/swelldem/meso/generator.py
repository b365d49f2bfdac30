# SPDX-License-Identifier: GPL-2.0-or-later
"""Generation of a concrete mesostructure (aggregates + disc packing + Laguerre contacts).

Phases (timed in ``Assembly.stats["timings_s"]``):

1. aggregates: convex polygons drawn from the grading and placed largest first
   (:mod:`swelldem.meso.aggregates`, Python);
2. packing: one compact random disc packing of the whole specimen (C++);
3. laguerre: power diagram of the discs with CGAL, cells clipped to the specimen (C++);
4. labelling: discs -> mortar / aggregate, facets -> contacts and their kind, checks.
"""
import time

import numpy as np

from . import _geom
from .aggregates import draw_aggregates, place_aggregates
from .assembly import AGG, AGGREGATE_MATERIAL, ITZ, MORTAR, Assembly
from .params import MesoParameterError, MesoParameters

MM = 1e-3  # metres per millimetre

#: Stated overlap tolerance: no two discs overlap by more than this x Rmax (the packing
#: places discs tangent to each other; overlaps found are rounding errors, ~1e-14 Rmax).
OVERLAP_TOLERANCE_RATIO = 1e-9


def _check_seed(seed):
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not (0 <= int(seed) < 2 ** 63):
        raise MesoParameterError("seed", seed, "must be an integer in [0, 2**63)")
    return int(seed)


def label_discs(x, y, r, polygons, rule="centre"):
    """Aggregate id of every disc (-1 mortar), all lengths in one unit.

    rule "centre": a disc belongs to a polygon when its centre is inside it (or on its
    contour); rule "inside": when the whole disc is inside it.
    """
    agg = np.full(len(x), -1, dtype=np.int32)
    for k, v in enumerate(polygons):
        lo = v.min(axis=0)
        hi = v.max(axis=0)
        cand = np.nonzero((x >= lo[0]) & (x <= hi[0]) & (y >= lo[1]) & (y <= hi[1]))[0]
        if cand.size == 0:
            continue
        e = np.roll(v, -1, axis=0) - v
        L = np.hypot(e[:, 0], e[:, 1])
        # signed distance of the centres to every edge line, positive inside (CCW polygon)
        sd = (-(x[cand, None] - v[None, :, 0]) * e[None, :, 1]
              + (y[cand, None] - v[None, :, 1]) * e[None, :, 0]) / L[None, :]
        inner = sd.min(axis=1)
        need = 0.0 if rule == "centre" else r[cand]
        inside = inner >= need
        agg[cand[inside]] = k
    return agg


def contact_kinds(i, j, aggregate_id):
    """MORTAR (0) for mortar-mortar, AGG (2) for two discs of one aggregate, else ITZ (1)."""
    ai, aj = aggregate_id[i], aggregate_id[j]
    kind = np.full(len(i), ITZ, dtype=np.int8)
    kind[(ai < 0) & (aj < 0)] = MORTAR
    kind[(ai >= 0) & (ai == aj)] = AGG
    return kind


def generate(params=None, seed=0, **overrides):
    """Generate a concrete mesostructure; returns an :class:`Assembly` in SI metres.

    Args:
        params: a :class:`MesoParameters` (default: the paper's setting, 100 x 100 mm).
        seed: integer in [0, 2**63); the same seed and parameters give an identical assembly.
        **overrides: fields of MesoParameters to change, e.g. ``width_mm=30, height_mm=30``
            (lengths in mm, see MesoParameters).

    Raises:
        MesoParameterError: a parameter is out of range (before any work starts).
        AggregatePlacementError: the aggregates could not be placed.
    """
    p = params if params is not None else MesoParameters()
    if not isinstance(p, MesoParameters):
        raise MesoParameterError("params", p, "must be a MesoParameters instance or None")
    if overrides:
        p = p.replace(**overrides)
    p.validate()
    seed = _check_seed(seed)
    t_start = time.perf_counter()
    timings = {}

    ss = np.random.SeedSequence(seed)
    agg_seq, pack_seq = ss.spawn(2)
    rng = np.random.default_rng(agg_seq)
    pack_seed = int(pack_seq.generate_state(1, dtype=np.uint64)[0])

    W, H = float(p.width_mm), float(p.height_mm)
    # 1. aggregates
    t = time.perf_counter()
    aggs = place_aggregates(p, draw_aggregates(p, rng), rng, seed=seed)
    timings["aggregates"] = time.perf_counter() - t

    # 2. packing (mm)
    t = time.perf_counter()
    x, y, r, pstats = _geom.pack_rectangle(W, H, p.rmin_mm, p.rmax_mm, pack_seed)
    timings["packing"] = time.perf_counter() - t

    # 3. Laguerre cells and facets (mm)
    t = time.perf_counter()
    lag = _geom.laguerre_rectangle(x, y, r, W, H)
    timings["laguerre"] = time.perf_counter() - t

    # 4. labels, contacts, checks
    t = time.perf_counter()
    polygons_mm = [a.vertices for a in aggs]
    agg_id = label_discs(x, y, r, polygons_mm, p.label_rule)
    material = (agg_id >= 0).astype(np.int8)
    fi, fj, flen = lag["i"], lag["j"], lag["length"]
    dist = np.hypot(x[fj] - x[fi], y[fj] - y[fi])
    gap = dist - r[fi] - r[fj]
    # gap tolerance; the 1e-9 Rmax term keeps tangencies whose computed gap is a rounding error above 0
    tol_mm = (p.contact_gap_ratio + OVERLAP_TOLERANCE_RATIO) * p.rmax_mm
    sel = gap <= tol_mm
    ci, cj = fi[sel], fj[sel]
    kind = contact_kinds(ci, cj, agg_id)
    contacts = np.stack([ci, cj], axis=1).astype(np.int32)
    facet_length_m = flen[sel] * MM
    facet_area_m2 = facet_length_m * p.thickness_m

    # checks reported in stats
    max_overlap_mm = _max_overlap(x, y, r, p.rmax_mm)
    outside = max(0.0, float(np.max(np.concatenate([r - x, x + r - W, r - y, y + r - H])))) if len(x) else 0.0
    cell_area_sum = float(lag["cell_area"].sum())
    poly_area = np.array([a.area for a in aggs])
    n_frac = len(p.sieve_fractions_mm)
    frac_idx = np.array([a.fraction for a in aggs], dtype=np.int32)
    area_by_frac = [float(poly_area[frac_idx == k].sum()) for k in range(n_frac)]
    tot_poly = float(poly_area.sum())
    discs_per_agg = np.bincount(agg_id[agg_id >= 0], minlength=len(aggs)) if len(aggs) else np.zeros(0, int)
    timings["labelling"] = time.perf_counter() - t
    wall = time.perf_counter() - t_start

    stats = {
        "aggregate_area_fraction": tot_poly / (W * H),
        "aggregate_area_fraction_target": float(p.aggregate_area_fraction),
        "aggregate_area_fraction_cells": float(lag["cell_area"][material == AGGREGATE_MATERIAL].sum() / (W * H)),
        "aggregate_area_by_fraction": [a / tot_poly if tot_poly > 0 else 0.0 for a in area_by_frac],
        "aggregates_by_fraction": [int((frac_idx == k).sum()) for k in range(n_frac)],
        "empty_aggregates": int((discs_per_agg == 0).sum()),
        "max_overlap_m": max_overlap_mm * MM,
        "max_outside_m": outside * MM,
        "cell_area_sum_rel_error": abs(cell_area_sum - W * H) / (W * H),
        "facet_asymmetry_max_m": float(lag["stats"]["max_asymmetry"]) * MM,
        "contact_gap_tolerance_m": tol_mm * MM,
        "laguerre_pairs": int(len(fi)),
        "laguerre_pairs_not_in_contact": int((~sel).sum()),
        "empty_cells": int(lag["stats"]["empty_cells"]),
        "packing_stats": {k: v for k, v in pstats.items()},
        "timings_s": timings,
        "wall_s": wall,
        "library_version": _geom.version(),
    }
    return Assembly(
        x=x * MM, y=y * MM, r=r * MM, material=material, aggregate_id=agg_id,
        cell_area_m2=lag["cell_area"] * MM * MM,
        contacts=contacts, kind=kind, facet_length_m=facet_length_m, facet_area_m2=facet_area_m2,
        distance_m=dist[sel] * MM, gap_m=gap[sel] * MM, facet_segment_m=lag["segment"][sel] * MM,
        neighbours=np.stack([fi, fj], axis=1).astype(np.int32), neighbour_facet_length_m=flen * MM,
        polygons=[v * MM for v in polygons_mm],
        aggregate_sieve_size_m=np.array([a.sieve_size for a in aggs], dtype=np.float64) * MM,
        aggregate_fraction=frac_idx,
        aggregate_aspect_ratio=np.array([a.aspect_ratio for a in aggs], dtype=np.float64),
        width_m=W * MM, height_m=H * MM, thickness_m=float(p.thickness_m), seed=seed,
        parameters=p.to_dict(), stats=stats)


def _max_overlap(x, y, r, rmax):
    """Largest overlap ri + rj - d over all pairs of discs (0 if none), via a k-d tree."""
    if len(x) < 2:
        return 0.0
    from scipy.spatial import cKDTree
    tree = cKDTree(np.stack([x, y], axis=1))
    pairs = tree.query_pairs(2 * rmax, output_type="ndarray")
    if len(pairs) == 0:
        return 0.0
    i, j = pairs[:, 0], pairs[:, 1]
    ov = r[i] + r[j] - np.hypot(x[i] - x[j], y[i] - y[j])
    return max(0.0, float(ov.max()))


def choose_contacts(assembly, kind, fraction, seed):
    """A seeded random choice of round(fraction x count) contacts of one kind (indices, sorted).

    kind: 0/1/2 or 'MORTAR'/'ITZ'/'AGG'; fraction in [0, 1]; seed: int (numpy SeedSequence).
    """
    if not 0.0 <= float(fraction) <= 1.0:
        raise ValueError(f"swelldem.meso.choose_contacts: fraction = {fraction} is out of range; allowed: [0, 1]")
    idx = assembly.contacts_of_kind(kind)
    k = int(round(float(fraction) * len(idx)))
    rng = np.random.default_rng(np.random.SeedSequence(int(seed)))
    return np.sort(rng.choice(idx, size=k, replace=False)) if k else np.zeros(0, dtype=np.int64)
