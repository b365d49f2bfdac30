# SPDX-License-Identifier: GPL-2.0-or-later
"""Tests of the compiled geometry library (disc packing, Laguerre facets) against independent checks.

Needs the library built (SWELLDEM_BUILD_DIR or <repo>/build): a missing library is a failure.
"""
import itertools

import numpy as np
import pytest

from swelldem.meso import _geom  # conftest puts py/ on the path

RMAX = 0.48
RMIN = 0.32


def pair_overlaps(x, y, r):
    """All pairwise overlaps ri + rj - d (brute force, i < j)."""
    d = np.hypot(x[:, None] - x[None, :], y[:, None] - y[None, :])
    ov = r[:, None] + r[None, :] - d
    iu = np.triu_indices(len(x), 1)
    return ov[iu]


@pytest.mark.parametrize("W,H,seed", [(12.0, 9.0, 0), (15.0, 15.0, 1), (20.0, 6.0, 2), (7.3, 11.1, 3), (3.0, 30.0, 4)])
def test_packing_no_overlap_inside_dense(W, H, seed):
    x, y, r, st = _geom.pack_rectangle(W, H, RMIN, RMAX, seed)
    assert len(x) == st["n"] > 10
    assert np.all(r >= RMIN * (1 - 1e-12)) and np.all(r <= RMAX * (1 + 1e-12))
    assert pair_overlaps(x, y, r).max() <= 1e-9 * RMAX
    tol = 1e-12 * max(W, H)
    assert np.all(x - r >= -tol) and np.all(x + r <= W + tol)
    assert np.all(y - r >= -tol) and np.all(y + r <= H + tol)
    density = np.pi * np.sum(r ** 2) / (W * H)
    assert density == pytest.approx(st["density"], rel=1e-12)
    assert density > 0.72  # small boxes lose density along their sides


def test_packing_density_large_box():
    x, y, r, st = _geom.pack_rectangle(40.0, 40.0, RMIN, RMAX, 7)
    assert st["density"] > 0.80
    # the radii follow the uniform law on [RMIN, RMAX]
    assert r.mean() == pytest.approx(0.5 * (RMIN + RMAX), rel=0.02)
    assert st["enlarged"] <= 0.001 * len(r)


def test_packing_deterministic():
    a = _geom.pack_rectangle(10.0, 8.0, RMIN, RMAX, 42)
    b = _geom.pack_rectangle(10.0, 8.0, RMIN, RMAX, 42)
    c = _geom.pack_rectangle(10.0, 8.0, RMIN, RMAX, 43)
    for u, v in zip(a[:3], b[:3]):
        assert np.array_equal(u, v)
    assert len(a[0]) != len(c[0]) or not np.array_equal(a[0], c[0])


@pytest.mark.parametrize("args,words", [
    ((10.0, 10.0, 0.5, 0.4), "rmin"),
    ((-1.0, 10.0, 0.3, 0.4), "width"),
    ((10.0, 0.5, 0.3, 0.4), "2 rmax"),
    ((10.0, 10.0, 0.0, 0.4), "rmin"),
])
def test_packing_bad_arguments(args, words):
    with pytest.raises(_geom.GeometryLibraryError, match=words):
        _geom.pack_rectangle(*args, 1)


# --------------------------------------------------------------------------- Laguerre


def brute_force_facets(x, y, r, W, H):
    """Facet length of every pair by clipping the power bisector line with all other
    half-planes and the box (1D interval clipping), independent of the library."""
    n = len(x)
    c = np.stack([x, y], axis=1)
    w = r ** 2
    out = {}
    for i, j in itertools.combinations(range(n), 2):
        nrm = 2 * (c[j] - c[i])
        rhs = c[j] @ c[j] - c[i] @ c[i] - w[j] + w[i]
        nn = nrm @ nrm
        p0 = nrm * rhs / nn
        d = np.array([-nrm[1], nrm[0]]) / np.sqrt(nn)
        lo, hi = -np.inf, np.inf
        cons = []
        for k in range(n):
            if k in (i, j):
                continue
            a = 2 * (c[k] - c[i])
            b = c[k] @ c[k] - c[i] @ c[i] - w[k] + w[i]
            cons.append((a, b))
        cons += [(np.array([-1.0, 0.0]), 0.0), (np.array([1.0, 0.0]), W),
                 (np.array([0.0, -1.0]), 0.0), (np.array([0.0, 1.0]), H)]
        for a, b in cons:
            ad = a @ d
            s = b - a @ p0
            if abs(ad) < 1e-15:
                if s < 0:
                    lo, hi = 1.0, 0.0
                continue
            t = s / ad
            if ad > 0:
                hi = min(hi, t)
            else:
                lo = max(lo, t)
        length = max(0.0, hi - lo)
        if length > 0:
            out[(i, j)] = length
    return out


def grid_cell_areas(x, y, r, W, H, m=400):
    """Cell areas by assigning the centres of an m x m grid of pixels to the smallest power distance."""
    gx = (np.arange(m) + 0.5) * W / m
    gy = (np.arange(m) + 0.5) * H / m
    px, py = np.meshgrid(gx, gy)
    pw = (px[..., None] - x) ** 2 + (py[..., None] - y) ** 2 - r ** 2
    owner = np.argmin(pw, axis=-1)
    return np.bincount(owner.ravel(), minlength=len(x)) * (W * H / m / m)


def random_discs(rng, n, W, H, rlo, rhi):
    """Non-overlapping discs with random radii and centres (rejection), not all touching."""
    xs, ys, rs = [], [], []
    while len(xs) < n:
        rr = rng.uniform(rlo, rhi)
        px, py = rng.uniform(rr, W - rr), rng.uniform(rr, H - rr)
        if all((px - a) ** 2 + (py - b) ** 2 >= (rr + c) ** 2 for a, b, c in zip(xs, ys, rs)):
            xs.append(px)
            ys.append(py)
            rs.append(rr)
    return np.array(xs), np.array(ys), np.array(rs)


def check_against_brute_force(x, y, r, W, H):
    res = _geom.laguerre_rectangle(x, y, r, W, H)
    cpp = {(int(i), int(j)): float(l) for i, j, l in zip(res["i"], res["j"], res["length"])}
    bf = brute_force_facets(x, y, r, W, H)
    scale = np.sqrt(W * H / len(x))
    for key in set(cpp) | set(bf):
        assert cpp.get(key, 0.0) == pytest.approx(bf.get(key, 0.0), abs=1e-9 * scale), key
    assert all(v > 0 for v in cpp.values())
    assert all(i < j for i, j in cpp)
    area = res["cell_area"]
    assert area.sum() == pytest.approx(W * H, rel=1e-12)
    assert np.all(area > 0)
    pix = grid_cell_areas(x, y, r, W, H)
    # pixel counting is accurate to about a perimeter x pixel size
    assert np.abs(area - pix).max() < 4 * (W / 400) * 2 * (W + H) / np.sqrt(len(x))
    # the facet end points lie on the power bisector of their two discs
    for (i, j), seg in zip(zip(res["i"], res["j"]), res["segment"]):
        for px, py in (seg[:2], seg[2:]):
            pi = (px - x[i]) ** 2 + (py - y[i]) ** 2 - r[i] ** 2
            pj = (px - x[j]) ** 2 + (py - y[j]) ** 2 - r[j] ** 2
            assert abs(pi - pj) < 1e-9 * scale ** 2
    return res


@pytest.mark.parametrize("seed", range(6))
def test_laguerre_matches_brute_force_random(seed):
    rng = np.random.default_rng(seed)
    W, H = rng.uniform(3, 6), rng.uniform(3, 6)
    n = int(rng.integers(5, 30))
    x, y, r = random_discs(rng, n, W, H, 0.05, 0.6)
    check_against_brute_force(x, y, r, W, H)


@pytest.mark.parametrize("seed", range(3))
def test_laguerre_matches_brute_force_packing(seed):
    x, y, r, _ = _geom.pack_rectangle(4.0, 3.5, RMIN, RMAX, seed)
    check_against_brute_force(x, y, r, 4.0, 3.5)


def test_laguerre_degenerate_square_lattice():
    # 4 co-circular centres everywhere: diagonal neighbours have zero-length facets
    s = 1.0
    g = (np.arange(5) + 0.5) * s
    x, y = [a.ravel() for a in np.meshgrid(g, g)]
    r = np.full(len(x), 0.5)
    res = check_against_brute_force(x, y, r, 5.0, 5.0)
    assert np.allclose(res["length"], s)
    assert len(res["length"]) == 2 * 5 * 4
    assert np.allclose(res["cell_area"], s * s)


def test_laguerre_collinear_and_single():
    x = np.array([1.0, 2.0, 3.5])
    y = np.array([1.0, 1.0, 1.0])
    r = np.array([0.4, 0.5, 0.3])
    res = check_against_brute_force(x, y, r, 5.0, 2.0)
    assert res["stats"]["dimension"] == 1
    one = _geom.laguerre_rectangle(np.array([0.5]), np.array([0.5]), np.array([0.2]), 2.0, 3.0)
    assert len(one["i"]) == 0 and one["cell_area"][0] == pytest.approx(6.0)


def test_laguerre_tiles_specimen_large():
    W, H = 30.0, 20.0
    x, y, r, _ = _geom.pack_rectangle(W, H, RMIN, RMAX, 11)
    res = _geom.laguerre_rectangle(x, y, r, W, H)
    assert abs(res["cell_area"].sum() - W * H) <= 1e-9 * W * H
    assert np.all(res["cell_area"] > 0)
    assert res["stats"]["empty_cells"] == 0
    assert res["stats"]["max_asymmetry"] < 1e-9 * RMAX
    assert np.all(res["length"] > 0)
    # each disc centre lies in its own cell: every disc has at least 2 facets or the box
    assert len(np.unique(np.concatenate([res["i"], res["j"]]))) == len(x)


def test_laguerre_bad_arguments():
    with pytest.raises(_geom.GeometryLibraryError, match="outside"):
        _geom.laguerre_rectangle(np.array([5.0]), np.array([0.5]), np.array([0.1]), 2.0, 2.0)
    with pytest.raises(_geom.GeometryLibraryError, match="negative"):
        _geom.laguerre_rectangle(np.array([1.0]), np.array([0.5]), np.array([-0.1]), 2.0, 2.0)
