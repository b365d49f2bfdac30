# SPDX-License-Identifier: GPL-2.0-or-later
"""Generation of a concrete mesostructure (aggregates + disc packing + Laguerre contacts).

``generate`` makes a 2D section (below) or, with ``dim=3``, a 3D box (:mod:`swelldem.meso.generator3d`).
2D phases (timed in ``Assembly.stats["timings_s"]``):

1. aggregates: convex polygons drawn from the grading and placed largest first
   (:mod:`swelldem.meso.aggregates`, Python);
2. packing: one compact random disc packing of the whole specimen (C++);
3. laguerre: power diagram of the discs with CGAL, cells clipped to the specimen (C++);
4. labelling: discs -> mortar / aggregate, facets -> contacts and their kind, checks.
"""
import functools
import time

import numpy as np

from . import _geom
from .aggregates import draw_aggregates, place_aggregates
from .assembly import AGGREGATE_MATERIAL, Assembly
from .params import MesoParameterError, MesoParameters

MM = 1e-3  # metres per millimetre

#: Stated overlap tolerance: no two discs overlap by more than this x Rmax (the packing
#: places discs tangent to each other; overlaps found are rounding errors, ~1e-14 Rmax).
OVERLAP_TOLERANCE_RATIO = 1e-9


def _check_seed(seed):
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not (0 <= int(seed) < 2 ** 63):
        raise MesoParameterError("seed", seed, "must be an integer in [0, 2**63)")
    return int(seed)


def seed_streams(seed):
    """The random streams of a seed, for both dimensions: numpy.random.SeedSequence(seed) spawns one
    stream for the aggregates (a numpy Generator) and one 64-bit seed for the C++ packing."""
    agg_seq, pack_seq = np.random.SeedSequence(seed).spawn(2)
    return np.random.default_rng(agg_seq), int(pack_seq.generate_state(1, dtype=np.uint64)[0])


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
    """Kind of the contacts (i, j): MORTAR (0) for mortar-mortar, AGG (2) for two discs of one
    aggregate, else ITZ (1); decided by the compiled rule the plugin's Ip2 applies to the discs'
    materials (pkg/core/PairKind.hpp), so that a scene's contacts get the assembly's kinds."""
    aggregate_id = np.asarray(aggregate_id)
    return _geom.pair_kinds(aggregate_id[np.asarray(i)], aggregate_id[np.asarray(j)])


def _hilbert_index(gx, gy, bits):
    """Distance along the Hilbert curve of the 2**bits x 2**bits grid of the integer cells (gx, gy)."""
    x, y = gx.astype(np.int64), gy.astype(np.int64)
    d = np.zeros(x.shape, dtype=np.int64)
    for level in range(bits - 1, -1, -1):
        s = np.int64(1) << level
        rx, ry = (x >> level) & 1, (y >> level) & 1
        d += s * s * ((3 * rx) ^ ry)
        x, y = x & (s - 1), y & (s - 1)
        # turn the quadrant's sub-square into the standard orientation of the curve
        turn = ry == 0
        flip = turn & (rx == 1)
        x, y = np.where(flip, s - 1 - x, x), np.where(flip, s - 1 - y, y)
        x, y = np.where(turn, y, x), np.where(turn, x, y)
    return d


def spatial_order(x, y, i, j, width, height, bits=16):
    """Renumbering of the discs along a Hilbert curve and of the disc pairs by their new numbers.

    x, y: disc centres in [0, width] x [0, height] (one length unit); i, j: the pairs' disc indices.
    Discs close in space get close numbers, so a loop over discs or over pairs sorted by their first
    disc walks memory in order. Ties (two centres in one grid cell) keep the old order.
    Returns (perm, q, i2, j2): new disc k is old disc perm[k]; new pair p is old pair q[p], between
    the new discs i2[p] < j2[p]; pairs sorted by (i2, j2).
    """
    n = np.int64(1) << bits
    side = max(float(width), float(height))
    gx = np.clip(np.floor(np.asarray(x) / side * n), 0, n - 1).astype(np.int64)
    gy = np.clip(np.floor(np.asarray(y) / side * n), 0, n - 1).astype(np.int64)
    perm = np.argsort(_hilbert_index(gx, gy, bits), kind="stable")
    new = np.empty(len(perm), dtype=np.int64)
    new[perm] = np.arange(len(perm))
    a, b = new[np.asarray(i, dtype=np.int64)], new[np.asarray(j, dtype=np.int64)]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    q = np.lexsort((hi, lo))
    return perm, q, lo[q].astype(np.int32), hi[q].astype(np.int32)


#: Disc numberings of generate(): "packing" (the packing's order of placement, contacts in the
#: Laguerre diagram's order; the default, which every documented figure uses) or "hilbert" (along a
#: Hilbert curve, contacts sorted by their discs: 15-26 % cheaper ADR iterations from 10k discs,
#: docs/performance.md 3.1; a renumbering moves results by round-off and draws other gel pockets
#: for ASR-coarse, so it is not the default).
ORDERS = ("packing", "hilbert")


def generate(params=None, seed=0, order="packing", **overrides):
    """Generate a concrete mesostructure; returns an :class:`Assembly` in SI metres.

    Args:
        params: a :class:`MesoParameters` (default: the paper's setting, 100 x 100 mm).
        seed: integer in [0, 2**63); the same seed and parameters give an identical assembly.
        order: numbering of discs and contacts, one of ORDERS; both give the same discs and contacts
            (same values, only renumbered); "packing" (default) as placed, "hilbert" in spatial order.
        **overrides: fields of MesoParameters to change, e.g. ``width_mm=30, height_mm=30``
            (lengths in mm, see MesoParameters); ``dim=3, depth_mm=30`` for a 3D box.

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
    if order not in ORDERS:
        raise MesoParameterError("order", order, f"must be one of {ORDERS}")
    if p.dim == 3:
        from .generator3d import generate_3d  # a 2D section does not load the polyhedra's code
        return generate_3d(p, seed, order)
    t_start = time.perf_counter()
    timings = {}

    rng, pack_seed = seed_streams(seed)

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

    # checks reported in stats
    max_overlap_mm = max_overlap(r, p.rmax_mm, x, y)
    outside = max(0.0, float(np.max(np.concatenate([r - x, x + r - W, r - y, y + r - H])))) if len(x) else 0.0
    cell_area_sum = float(lag["cell_area"].sum())
    cell_area_agg = float(lag["cell_area"][material == AGGREGATE_MATERIAL].sum())
    poly_area = np.array([a.area for a in aggs])
    n_frac = len(p.sieve_fractions_mm)
    frac_idx = np.array([a.fraction for a in aggs], dtype=np.int32)
    area_by_frac = [float(poly_area[frac_idx == k].sum()) for k in range(n_frac)]
    tot_poly = float(poly_area.sum())
    discs_per_agg = np.bincount(agg_id[agg_id >= 0], minlength=len(aggs)) if len(aggs) else np.zeros(0, int)
    timings["labelling"] = time.perf_counter() - t

    # 5. numbering: a permutation of the discs and of the pairs, after every figure is computed
    t = time.perf_counter()
    cell_area, segment = lag["cell_area"], lag["segment"]
    if order == "hilbert":
        perm, q, fi, fj = spatial_order(x, y, fi, fj, W, H)
        x, y, r, agg_id, material, cell_area = x[perm], y[perm], r[perm], agg_id[perm], material[perm], cell_area[perm]
        flen, segment, dist, gap, sel = flen[q], segment[q], dist[q], gap[q], sel[q]
    ci, cj = fi[sel], fj[sel]
    kind = contact_kinds(ci, cj, agg_id)
    contacts = np.stack([ci, cj], axis=1).astype(np.int32)
    facet_length_m = flen[sel] * MM
    facet_area_m2 = facet_length_m * p.thickness_m
    timings["ordering"] = time.perf_counter() - t
    wall = time.perf_counter() - t_start

    stats = {
        "aggregate_area_fraction": tot_poly / (W * H),
        "aggregate_area_fraction_target": float(p.aggregate_area_fraction),
        "aggregate_area_fraction_cells": cell_area_agg / (W * H),
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
        "order": order,
    }
    return Assembly(
        x=x * MM, y=y * MM, r=r * MM, material=material, aggregate_id=agg_id,
        cell_area_m2=cell_area * MM * MM,
        contacts=contacts, kind=kind, facet_length_m=facet_length_m, facet_area_m2=facet_area_m2,
        distance_m=dist[sel] * MM, gap_m=gap[sel] * MM, facet_segment_m=segment[sel] * MM,
        neighbours=np.stack([fi, fj], axis=1).astype(np.int32), neighbour_facet_length_m=flen * MM,
        polygons=[v * MM for v in polygons_mm],
        aggregate_sieve_size_m=np.array([a.sieve_size for a in aggs], dtype=np.float64) * MM,
        aggregate_fraction=frac_idx,
        aggregate_aspect_ratio=np.array([a.aspect_ratio for a in aggs], dtype=np.float64),
        width_m=W * MM, height_m=H * MM, thickness_m=float(p.thickness_m), seed=seed,
        parameters=p.to_dict(), stats=stats)


def max_overlap(r, rmax, *coords):
    """Largest overlap ri + rj - d over all pairs of discs or spheres (0 if none), via a k-d tree;
    coords: x, y (and z) of the centres."""
    if len(r) < 2:
        return 0.0
    from scipy.spatial import cKDTree
    pts = np.stack(coords, axis=1)
    pairs = cKDTree(pts).query_pairs(2 * rmax, output_type="ndarray")
    if len(pairs) == 0:
        return 0.0
    i, j = pairs[:, 0], pairs[:, 1]
    # hypot column by column: the 2D figure stays the one np.hypot(dx, dy) gave
    ov = r[i] + r[j] - functools.reduce(np.hypot, (pts[i] - pts[j]).T)
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
