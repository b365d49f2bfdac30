# SPDX-License-Identifier: GPL-2.0-or-later
"""Generation of a 3D concrete mesostructure (polyhedral aggregates + sphere packing + Laguerre facets).

The phases of the 2D generator, one dimension up (timed in ``Assembly.stats["timings_s"]``):

1. aggregates: convex polyhedra drawn from the grading and placed largest first
   (:mod:`swelldem.meso.aggregates3d`, Python);
2. packing: one random packing of spheres in the whole box (C++, collective rearrangement,
   numbered in Morton order);
3. laguerre: 3D power diagram of the spheres with CGAL, cells clipped to the box (C++);
4. labelling: spheres -> mortar / aggregate (the centre rule of 2D), facets -> contacts and their
   kind by the plugin's one rule (pkg/core/PairKind.hpp, through ``_geom.pair_kinds``).

Contacts are the Laguerre neighbours whose gap is within ``contact_gap_ratio`` x Rmax, as in 2D;
the other neighbours are kept in ``Assembly.neighbours`` with their facet areas, for contacts that
a later compression closes.
"""
import time

import numpy as np

from . import _geom
from .aggregates3d import draw_polyhedra, label_spheres, place_polyhedra
from .assembly import AGGREGATE_MATERIAL, Assembly
from .generator import OVERLAP_TOLERANCE_RATIO, max_overlap, seed_streams
from .params import MesoParameterError

MM = 1e-3  # metres per millimetre


def generate_3d(p, seed, order="packing"):
    """The 3D case of :func:`swelldem.meso.generate` (p validated, dim 3, seed checked)."""
    if order != "packing":
        raise MesoParameterError("order", order, "must be 'packing' in 3D: the sphere packing is numbered "
                                 "along a Morton curve already")
    t_start = time.perf_counter()
    timings = {}
    rng, pack_seed = seed_streams(seed)
    W, H, D = float(p.width_mm), float(p.height_mm), float(p.depth_mm)
    box_volume = W * H * D

    t = time.perf_counter()
    aggs = place_polyhedra(p, draw_polyhedra(p, rng), rng, seed=seed) if p.aggregate_area_fraction > 0 else []
    timings["aggregates"] = time.perf_counter() - t

    t = time.perf_counter()
    x, y, z, r, pstats = _geom.pack_box(W, H, D, p.rmin_mm, p.rmax_mm, pack_seed)
    timings["packing"] = time.perf_counter() - t

    t = time.perf_counter()
    lag = _geom.laguerre_box(x, y, z, r, W, H, D)
    timings["laguerre"] = time.perf_counter() - t

    t = time.perf_counter()
    agg_id = label_spheres(x, y, z, r, aggs, p.label_rule) if aggs else np.full(len(x), -1, dtype=np.int32)
    material = (agg_id >= 0).astype(np.int8)
    fi, fj = lag["i"], lag["j"]
    dist = np.sqrt((x[fj] - x[fi]) ** 2 + (y[fj] - y[fi]) ** 2 + (z[fj] - z[fi]) ** 2)
    gap = dist - r[fi] - r[fj]
    tol_mm = (p.contact_gap_ratio + OVERLAP_TOLERANCE_RATIO) * p.rmax_mm
    sel = gap <= tol_mm
    ci, cj = fi[sel], fj[sel]
    kind = _geom.pair_kinds(agg_id[ci], agg_id[cj])
    off, verts = lag["polygon_offset"], lag["polygon_vertices"]
    facet_polygons = [verts[off[k]:off[k + 1]] * MM for k in np.flatnonzero(sel)]

    max_overlap_mm = max_overlap(r, p.rmax_mm, x, y, z)
    outside = max(0.0, float(np.max(np.concatenate([r - x, x + r - W, r - y, y + r - H, r - z, z + r - D])))) \
        if len(x) else 0.0
    cell_volume = lag["cell_volume"]
    vol = np.array([a.volume for a in aggs])
    n_frac = len(p.sieve_fractions_mm)
    frac_idx = np.array([a.fraction for a in aggs], dtype=np.int32)
    tot = float(vol.sum())
    per_agg = np.bincount(agg_id[agg_id >= 0], minlength=len(aggs)) if len(aggs) else np.zeros(0, int)
    timings["labelling"] = time.perf_counter() - t
    wall = time.perf_counter() - t_start

    stats = {
        "aggregate_volume_fraction": tot / box_volume,
        "aggregate_volume_fraction_target": float(p.aggregate_area_fraction),
        "aggregate_volume_fraction_cells": float(cell_volume[material == AGGREGATE_MATERIAL].sum()) / box_volume,
        "aggregate_volume_by_fraction": [float(vol[frac_idx == k].sum()) / tot if tot > 0 else 0.0 for k in range(n_frac)],
        "aggregates_by_fraction": [int((frac_idx == k).sum()) for k in range(n_frac)],
        "empty_aggregates": int((per_agg == 0).sum()),
        "max_overlap_m": max_overlap_mm * MM,
        "max_outside_m": outside * MM,
        "cell_volume_sum_rel_error": abs(float(cell_volume.sum()) - box_volume) / box_volume,
        "facet_asymmetry_max_m": float(lag["stats"]["max_asymmetry"]) * MM,
        "contact_gap_tolerance_m": tol_mm * MM,
        "laguerre_pairs": int(len(fi)),
        "laguerre_pairs_not_in_contact": int((~sel).sum()),
        # rattlers: the packing's relaxation leaves no exact tangency, so a sphere whose neighbours all
        # sit beyond the gap tolerance has no contact (a few per thousand at 0.05 Rmax)
        "spheres_without_contact": int((np.bincount(np.concatenate([ci, cj]), minlength=len(x)) == 0).sum()),
        "empty_cells": int(lag["stats"]["empty_cells"]),
        "hidden_spheres": int(lag["stats"]["hidden"]),
        "packing_stats": dict(pstats),
        "timings_s": timings,
        "wall_s": wall,
        "library_version": _geom.version(),
        "order": order,
    }
    return Assembly(
        dim=3, x=x * MM, y=y * MM, z=z * MM, r=r * MM, material=material, aggregate_id=agg_id,
        cell_area_m2=None, cell_volume_m3=cell_volume * MM ** 3,
        contacts=np.stack([ci, cj], axis=1).astype(np.int32), kind=kind,
        facet_length_m=None, facet_area_m2=lag["area"][sel] * MM * MM,
        distance_m=dist[sel] * MM, gap_m=gap[sel] * MM, facet_segment_m=None,
        facet_normal=lag["normal"][sel].copy(), facet_centroid_m=lag["centroid"][sel] * MM,
        facet_polygons=facet_polygons,
        neighbours=np.stack([fi, fj], axis=1).astype(np.int32), neighbour_facet_length_m=None,
        neighbour_facet_area_m2=lag["area"] * MM * MM,
        polygons=[], polyhedra=[a.vertices * MM for a in aggs],
        aggregate_sieve_size_m=np.array([a.sieve_size for a in aggs], dtype=np.float64) * MM,
        aggregate_fraction=frac_idx,
        aggregate_aspect_ratio=np.array([a.aspect_ratio for a in aggs], dtype=np.float64),
        width_m=W * MM, height_m=H * MM, depth_m=D * MM, thickness_m=float(p.thickness_m), seed=seed,
        parameters=p.to_dict(), stats=stats)
