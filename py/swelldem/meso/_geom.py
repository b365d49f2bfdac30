# SPDX-License-Identifier: GPL-2.0-or-later
"""ctypes binding of the compiled geometry library ``libswelldem_geom.so``.

The C functions are unit-agnostic; this module passes whatever unit it is given
(the generator uses millimetres) and returns numpy arrays in the same unit.
"""
import ctypes
import math

import numpy as np

from .. import paths

_LIB = None
_LIB_RELPATH = "pkg/meso/libswelldem_geom.so"

_dp = ctypes.POINTER(ctypes.c_double)
_ip = ctypes.POINTER(ctypes.c_int)
_lp = ctypes.POINTER(ctypes.c_long)
_LONG = np.dtype(ctypes.c_long)


class GeometryLibraryError(RuntimeError):
    """An error reported by the compiled geometry library."""


def library_path():
    """Absolute path of libswelldem_geom.so in the build folder (raises if it is not built)."""
    return paths.built_library(_LIB_RELPATH)


def lib():
    """The loaded library (loaded once)."""
    global _LIB
    if _LIB is None:
        handle = ctypes.CDLL(library_path())
        handle.swd_geom_version.restype = ctypes.c_char_p
        handle.swd_geom_version.argtypes = []
        handle.swd_geom_last_error.restype = ctypes.c_char_p
        handle.swd_geom_last_error.argtypes = []
        handle.swd_pack_rectangle.restype = ctypes.c_long
        handle.swd_pack_rectangle.argtypes = [
            ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_double,
            ctypes.c_ulonglong, ctypes.c_long, _dp, _dp, _dp, _dp]
        handle.swd_pack_box.restype = ctypes.c_long
        handle.swd_pack_box.argtypes = [
            ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_double, ctypes.c_double,
            ctypes.c_ulonglong, ctypes.c_long, _dp, _dp, _dp, _dp, _dp]
        handle.swd_laguerre_rectangle.restype = ctypes.c_long
        handle.swd_laguerre_rectangle.argtypes = [
            ctypes.c_long, _dp, _dp, _dp, ctypes.c_double, ctypes.c_double, ctypes.c_long,
            _ip, _ip, _dp, _dp, _dp, _dp]
        handle.swd_laguerre_box.restype = ctypes.c_long
        handle.swd_laguerre_box.argtypes = [
            ctypes.c_long, _dp, _dp, _dp, _dp, ctypes.c_double, ctypes.c_double, ctypes.c_double,
            ctypes.c_long, ctypes.c_long, _ip, _ip, _dp, _dp, _dp, _lp, _dp, _dp, _dp, _lp, _dp]
        handle.swd_pair_kinds.restype = ctypes.c_long
        handle.swd_pair_kinds.argtypes = [ctypes.c_long, _ip, _ip, _ip]
        _LIB = handle
    return _LIB


def version():
    """Version string of the compiled library."""
    return lib().swd_geom_version().decode()


def _ptr(a, ctype=_dp):
    return a.ctypes.data_as(ctype)


def _raise():
    msg = lib().swd_geom_last_error().decode() or "unknown error"
    raise GeometryLibraryError(msg)


PACK_STAT_NAMES = ("density", "n", "abandoned_pairs", "top_fill", "collapses",
                   "max_overlap_rel", "enlarged", "reserved")
LAGUERRE_STAT_NAMES = ("area_sum", "max_asymmetry", "empty_cells", "dimension",
                       "neighbour_pairs", "zero_length_pairs", "zero_threshold", "reserved")


def pack_rectangle(width, height, rmin, rmax, seed):
    """Compact random disc packing of [0,width]x[0,height] (any length unit).

    Returns (x, y, r, stats) with numpy float64 arrays and a dict of statistics
    (``density`` = disc area / box area, ...).
    """
    seed = int(seed)
    if seed < 0 or seed >= 2 ** 64:
        raise ValueError(f"seed = {seed} must be in [0, 2**64)")
    try:
        cap = int(math.floor(width * height / (math.pi * rmin * rmin))) + 16
    except (ZeroDivisionError, OverflowError, ValueError):
        cap = 16  # invalid arguments: the library reports them
    cap = min(max(cap, 16), 50_000_000)
    x = np.empty(cap)
    y = np.empty(cap)
    r = np.empty(cap)
    st = np.zeros(8)
    n = lib().swd_pack_rectangle(float(width), float(height), float(rmin), float(rmax),
                                 ctypes.c_ulonglong(seed), cap, _ptr(x), _ptr(y), _ptr(r), _ptr(st))
    if n < 0:
        _raise()
    stats = dict(zip(PACK_STAT_NAMES, st.tolist()))
    stats.pop("reserved")
    for k in ("n", "abandoned_pairs", "top_fill", "collapses", "enlarged"):
        stats[k] = int(stats[k])
    return x[:n].copy(), y[:n].copy(), r[:n].copy(), stats


PACK3D_STAT_NAMES = ("density", "n", "target_density", "sweeps", "pushes", "max_overlap_rel", "removed",
                     "near_contacts_per_sphere")


def pack_box(width, height, depth, rmin, rmax, seed):
    """Random packing of non-overlapping spheres in the box [0,width]x[0,height]x[0,depth].

    Any length unit L, the same for all five lengths (the generator uses mm; [m] works as well):
    radii uniform in [rmin, rmax] [L], every sphere inside the box. Collective rearrangement
    (pkg/meso/packing3d.cpp): radii filling 0.60 of the box at random centres, overlapping pairs
    of slightly inflated spheres pushed apart until none overlaps at the true radii. The spheres are numbered in Morton
    (Z-curve) order of the cubic cells of side rmin holding their centres.

    Returns (x, y, z, r, stats): numpy float64 arrays [L] and a dict: ``density`` (sphere volume /
    box volume), ``n``, ``target_density`` (of the radii drawn), ``sweeps`` and ``pushes`` (of the
    overlap removal), ``max_overlap_rel`` (worst overlap / rmax of the library's final check, <= 0
    when none), ``removed`` (spheres dropped to unjam it), ``near_contacts_per_sphere`` (pairs with a
    gap below 0.025 rmax, per sphere). Raises GeometryLibraryError on bad input (the message names
    the argument and its range) and ValueError on a seed outside [0, 2**64).
    """
    seed = int(seed)
    if seed < 0 or seed >= 2 ** 64:
        raise ValueError(f"seed = {seed} must be in [0, 2**64)")
    try:
        cap = int(math.floor(width * height * depth / (4 / 3 * math.pi * rmin ** 3))) + 16
    except (ZeroDivisionError, OverflowError, ValueError, TypeError):
        cap = 16  # invalid arguments: the library reports them
    cap = min(max(cap, 16), 100_000_000)
    x, y, z, r = (np.empty(cap) for _ in range(4))
    st = np.zeros(8)
    n = lib().swd_pack_box(float(width), float(height), float(depth), float(rmin), float(rmax),
                           ctypes.c_ulonglong(seed), cap, _ptr(x), _ptr(y), _ptr(z), _ptr(r), _ptr(st))
    if n < 0:
        _raise()
    stats = dict(zip(PACK3D_STAT_NAMES, st.tolist()))
    for k in ("n", "sweeps", "pushes", "removed"):
        stats[k] = int(stats[k])
    return x[:n].copy(), y[:n].copy(), z[:n].copy(), r[:n].copy(), stats


def laguerre_rectangle(x, y, r, width, height):
    """Laguerre (power) cells of discs clipped to [0,width]x[0,height] (any length unit).

    Returns a dict with ``cell_area`` (n), ``i``, ``j`` (int32, i < j), ``length``
    (facet length) and ``segment`` (m x 4: x1, y1, x2, y2) for every pair of discs
    whose clipped cells share an edge of positive length, and ``stats``.
    """
    x = np.ascontiguousarray(x, dtype=np.float64)
    y = np.ascontiguousarray(y, dtype=np.float64)
    r = np.ascontiguousarray(r, dtype=np.float64)
    n = len(x)
    if len(y) != n or len(r) != n:
        raise ValueError("x, y and r must have the same length")
    cap = 3 * n + 8
    fi = np.empty(cap, dtype=np.int32)
    fj = np.empty(cap, dtype=np.int32)
    fl = np.empty(cap)
    fs = np.empty(4 * cap)
    area = np.empty(max(n, 1))
    st = np.zeros(8)
    m = lib().swd_laguerre_rectangle(n, _ptr(x), _ptr(y), _ptr(r), float(width), float(height), cap,
                                     _ptr(fi, _ip), _ptr(fj, _ip), _ptr(fl), _ptr(fs), _ptr(area), _ptr(st))
    if m < 0:
        _raise()
    stats = dict(zip(LAGUERRE_STAT_NAMES, st.tolist()))
    stats.pop("reserved")
    for k in ("empty_cells", "dimension", "neighbour_pairs", "zero_length_pairs"):
        stats[k] = int(stats[k])
    return {"cell_area": area[:n].copy(), "i": fi[:m].copy(), "j": fj[:m].copy(),
            "length": fl[:m].copy(), "segment": fs[:4 * m].reshape(m, 4).copy(), "stats": stats}

LAGUERRE3D_STAT_NAMES = ("volume_sum", "max_asymmetry", "hidden", "empty_cells", "dimension",
                         "neighbour_pairs", "zero_area_pairs", "zero_threshold", "cap_sorts",
                         "reserved1", "reserved2", "reserved3")
#: Order of the columns of ``box_area``: the box sides and their outward normals.
BOX_SIDES = ("x=0", "x=W", "y=0", "y=H", "z=0", "z=D")
# Facets (pairs) a sphere allowed for at the first call: random packings have 6 to 7 pairs a sphere
# and about 5 vertices a facet (bench_laguerre3d.py).
_FACETS_PER_SPHERE_GUESS = 10
BOX_NORMALS = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]], dtype=np.float64)


def laguerre_box(x, y, z, r, width, height, depth, polygons=True):
    """Laguerre (power) cells of spheres clipped to the box [0,width]x[0,height]x[0,depth].

    Any length unit L (the generator uses mm); centres must lie in the box and radii be > 0.
    Power of a point p for sphere k: |p - c_k|^2 - r_k^2. Returns a dict of numpy arrays:

    - ``cell_volume`` (n) [L^3]: volume of every clipped cell;
    - ``box_area`` (n x 6) [L^2]: each cell's area on the box sides ``BOX_SIDES``
      (x=0, x=W, y=0, y=H, z=0, z=D; outward normals ``BOX_NORMALS``);
    - for the m pairs i < j whose cells share a face of area above ``stats["zero_threshold"]``,
      sorted by (i, j): ``i``, ``j`` (int32), ``area`` (m) [L^2, mean of the areas seen from
      both cells], ``normal`` (m x 3, unit, from centre i towards centre j) and ``centroid``
      (m x 3) [L];
    - with ``polygons``: ``polygon_offset`` (m + 1, C long) and ``polygon_vertices`` (k x 3) [L]:
      facet q is ``polygon_vertices[polygon_offset[q]:polygon_offset[q + 1]]``, counter-clockwise
      about its normal;
    - ``stats``: ``volume_sum`` [L^3], ``max_asymmetry`` [L^2] (max difference of a pair's area
      seen from its two cells), ``hidden`` (spheres without a cell in the triangulation),
      ``empty_cells`` (zero volume, hidden included), ``dimension`` (of the triangulation),
      ``neighbour_pairs`` (its edges), ``zero_area_pairs`` (edges without a facet),
      ``zero_threshold`` [L^2] and ``cap_sorts`` (clips ordered by angle; 0 expected).

    Raises GeometryLibraryError on bad input (the message names the argument and its range).
    """
    x = np.ascontiguousarray(x, dtype=np.float64)
    y = np.ascontiguousarray(y, dtype=np.float64)
    z = np.ascontiguousarray(z, dtype=np.float64)
    r = np.ascontiguousarray(r, dtype=np.float64)
    if not (x.ndim == y.ndim == z.ndim == r.ndim == 1):
        raise ValueError("x, y, z and r must be 1-D arrays")
    n = len(x)
    if len(y) != n or len(z) != n or len(r) != n:
        raise ValueError(f"x, y, z and r must have the same length (got {len(x)}, {len(y)}, {len(z)}, {len(r)})")
    # The library says how much it needs when the first guess is not enough; then the call is repeated.
    cap = _FACETS_PER_SPHERE_GUESS * n + 64
    vcap = 8 * cap if polygons else 0
    area_v = np.empty(max(n, 1))
    box = np.empty(6 * max(n, 1))
    st = np.zeros(12)
    needed = np.zeros(2, dtype=_LONG)
    for _ in range(2):
        fi = np.empty(cap, dtype=np.int32)
        fj = np.empty(cap, dtype=np.int32)
        fa = np.empty(cap)
        fn = np.empty(3 * cap)
        fc = np.empty(3 * cap)
        fo = np.empty(cap + 1, dtype=_LONG)
        fv = np.empty(3 * max(vcap, 1))
        m = lib().swd_laguerre_box(n, _ptr(x), _ptr(y), _ptr(z), _ptr(r), float(width), float(height),
                                   float(depth), cap, vcap, _ptr(fi, _ip), _ptr(fj, _ip), _ptr(fa), _ptr(fn),
                                   _ptr(fc), _ptr(fo, _lp), _ptr(fv) if polygons else None, _ptr(area_v),
                                   _ptr(box), _ptr(needed, _lp), _ptr(st))
        if m >= 0:
            break
        if needed[0] <= cap and (not polygons or needed[1] <= vcap):
            _raise()
        cap, vcap = max(cap, int(needed[0])), max(vcap, int(needed[1])) if polygons else 0
    else:
        _raise()
    stats = dict(zip(LAGUERRE3D_STAT_NAMES, st.tolist()))
    for k in ("reserved1", "reserved2", "reserved3"):
        stats.pop(k)
    for k in ("hidden", "empty_cells", "dimension", "neighbour_pairs", "zero_area_pairs", "cap_sorts"):
        stats[k] = int(stats[k])
    out = {"cell_volume": area_v[:n].copy(), "box_area": box[:6 * n].reshape(n, 6).copy(),
           "i": fi[:m].copy(), "j": fj[:m].copy(), "area": fa[:m].copy(),
           "normal": fn[:3 * m].reshape(m, 3).copy(), "centroid": fc[:3 * m].reshape(m, 3).copy(),
           "stats": stats}
    if polygons:
        nv = int(fo[m])
        out["polygon_offset"] = fo[:m + 1].copy()
        out["polygon_vertices"] = fv[:3 * nv].reshape(nv, 3).copy()
    return out


def pair_kinds(aggregate1, aggregate2):
    """Contact kind (0 MORTAR, 1 ITZ, 2 AGG; int8) of the pairs of concrete particles with these
    aggregate ids (-1 mortar), by the plugin's Ip2 rule (pkg/core/PairKind.hpp)."""
    a = np.ascontiguousarray(aggregate1, dtype=np.int32)
    b = np.ascontiguousarray(aggregate2, dtype=np.int32)
    if a.shape != b.shape or a.ndim != 1:
        raise ValueError("aggregate1 and aggregate2 must be 1-D arrays of the same length")
    kind = np.empty(len(a), dtype=np.int32)
    if lib().swd_pair_kinds(len(a), _ptr(a, _ip), _ptr(b, _ip), _ptr(kind, _ip)) < 0:
        _raise()
    return kind.astype(np.int8)
