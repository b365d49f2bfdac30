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
        handle.swd_laguerre_rectangle.restype = ctypes.c_long
        handle.swd_laguerre_rectangle.argtypes = [
            ctypes.c_long, _dp, _dp, _dp, ctypes.c_double, ctypes.c_double, ctypes.c_long,
            _ip, _ip, _dp, _dp, _dp, _dp]
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
