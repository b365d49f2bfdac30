# SPDX-License-Identifier: GPL-2.0-or-later
"""Tests of the 3D power (Laguerre) cells of spheres clipped to a box (_geom.laguerre_box)
against closed forms and checks made here, independently of the library.

Needs the library built (SWELLDEM_BUILD_DIR or <repo>/build): a missing library is a failure.

Tolerances were set from the errors measured on this machine (RelWithDebInfo, x86-64,
GCC 12, CGAL 5.5), with a margin of 40 or more:
- lattices (closed forms): facet areas and cell volumes within 2.4e-15 relative, normals
  within 1.1e-16, tiling and closure within 4.2e-16: LATTICE_REL = 1e-13;
- random packings: cell volumes sum to the box volume within 3.4e-16 relative, box pieces
  to each side within 3.0e-16, cells close within 3.6e-16 of their surface (1.3e-14 among
  heavily overlapping spheres): RANDOM_REL = 1e-9, the acceptance criterion of issue 26;
- facet vertices on the power diagram, facet polygon areas and the asymmetry of the two
  sides within 6e-15 of spacing^2 (1.4e-14 with overlaps): POWER_REL = 1e-12.
"""
import itertools
import math

import numpy as np
import pytest

from swelldem.meso import _geom  # conftest puts py/ on the path

RMAX = 0.48
RMIN = 0.32

LATTICE_REL = 1e-13      # measured <= 2.4e-15
RANDOM_REL = 1e-9        # the acceptance criterion; measured <= 1.3e-14
POWER_REL = 1e-12        # measured <= 1.4e-14


def laguerre(c, r, box, **kw):
    return _geom.laguerre_box(c[:, 0], c[:, 1], c[:, 2], r, *box, **kw)


def fcc_lattice(a, n):
    """Face-centred cubic lattice of nearest-neighbour spacing a, n x n x n cubic cells
    (side a sqrt 2) shifted by a quarter cell, and the box that holds it."""
    side = a * math.sqrt(2)
    basis = np.array([[0, 0, 0], [0, 0.5, 0.5], [0.5, 0, 0.5], [0.5, 0.5, 0]])
    g = np.arange(n)
    cells = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 1, 3)
    c = (cells + basis + 0.25).reshape(-1, 3) * side
    return c, (n * side,) * 3


def simple_cubic(a, nx, ny, nz):
    axes = [(np.arange(m) + 0.5) * a for m in (nx, ny, nz)]
    c = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    return c, (nx * a, ny * a, nz * a)


def random_spheres(rng, n, box, rlo=RMIN, rhi=RMAX, tries=200_000, batch=4000):
    """Up to n non-overlapping spheres inside the box by random sequential addition
    (candidates drawn in batches, each tested against those already placed)."""
    box = np.asarray(box, dtype=float)
    c = np.empty((0, 3))
    r = np.empty(0)
    for _ in range(tries // batch):
        rr = rng.uniform(rlo, rhi, batch)
        p = rng.uniform(rr[:, None], box - rr[:, None])
        d2 = np.sum((p[:, None, :] - c[None, :, :]) ** 2, axis=-1)
        for k in np.flatnonzero(np.all(d2 >= (rr[:, None] + r[None, :]) ** 2, axis=1)):
            if len(r) == n:
                return c, r
            if np.all(np.sum((c - p[k]) ** 2, axis=1) >= (r + rr[k]) ** 2):  # and those of this batch
                c = np.vstack([c, p[k]])
                r = np.append(r, rr[k])
    return c, r


def facets_of(res, k):
    """Indices of the facets of sphere k and the sign that turns their normal outward of k."""
    mine = np.flatnonzero(res["i"] == k)
    theirs = np.flatnonzero(res["j"] == k)
    return np.concatenate([mine, theirs]), np.concatenate([np.ones(len(mine)), -np.ones(len(theirs))])


def closure_errors(res):
    """Per sphere |sum of area x outward normal| over its facets and box pieces, and its
    cell's surface area."""
    n = len(res["cell_volume"])
    vec = res["box_area"] @ _geom.BOX_NORMALS
    surf = res["box_area"].sum(axis=1).copy()
    an = res["area"][:, None] * res["normal"]
    np.add.at(vec, res["i"], an)
    np.add.at(vec, res["j"], -an)
    np.add.at(surf, res["i"], res["area"])
    np.add.at(surf, res["j"], res["area"])
    assert vec.shape == (n, 3)
    return np.linalg.norm(vec, axis=1), surf


def polygon_vector_area(p):
    return 0.5 * np.sum(np.cross(p - p[0], np.roll(p, -1, axis=0) - p[0]), axis=0)


def power(p, c, r):
    return np.sum((p[:, None, :] - c[None, :, :]) ** 2, axis=-1) - r ** 2


def check_tiling(res, box, rel):
    """Cell volumes fill the box, box pieces fill each side, every cell is closed."""
    W, H, D = box
    vol = W * H * D
    assert abs(res["cell_volume"].sum() - vol) <= rel * vol
    assert abs(res["stats"]["volume_sum"] - vol) <= rel * vol
    side_area = np.array([H * D, H * D, W * D, W * D, W * H, W * H])
    assert np.all(np.abs(res["box_area"].sum(axis=0) - side_area) <= rel * side_area)
    err, surf = closure_errors(res)
    live = res["cell_volume"] > 0
    assert np.all(err[live] <= rel * surf[live])
    assert np.all(err[~live] == 0)


def check_on_power_diagram(res, c, r, box, rel):
    """Every facet polygon vertex is as near (in power) to i as to j and to no sphere
    nearer; the polygon is flat, perpendicular to the normal, of the reported area."""
    scale2 = (np.prod(box) / len(r)) ** (2 / 3)
    verts = res["polygon_vertices"]
    off = res["polygon_offset"]
    owner = np.repeat(np.arange(len(res["i"])), np.diff(off))
    pw = power(verts, c, r)
    pi = pw[np.arange(len(verts)), res["i"][owner]]
    pj = pw[np.arange(len(verts)), res["j"][owner]]
    assert np.all(np.abs(pi - pj) <= rel * scale2)
    assert np.all(pi - pw.min(axis=1) <= rel * scale2)
    for q in range(len(res["i"])):
        p = verts[off[q]:off[q + 1]]
        va = polygon_vector_area(p)
        assert va @ res["normal"][q] == pytest.approx(res["area"][q], rel=rel, abs=rel * scale2)
        assert np.linalg.norm(va - (va @ res["normal"][q]) * res["normal"][q]) <= rel * scale2
        # the reported centroid lies on the facet's plane
        assert abs((res["centroid"][q] - p[0]) @ res["normal"][q]) <= rel * math.sqrt(scale2)


# --------------------------------------------------------------------------- lattices


@pytest.mark.parametrize("a", [1.0, 0.87])
def test_fcc_interior_cells_are_rhombic_dodecahedra(a):
    n = 4
    c, box = fcc_lattice(a, n)
    r = np.full(len(c), a / 2)
    res = laguerre(c, r, box)
    side = a * math.sqrt(2)
    # the cell reaches half a cubic cell along the axes: interior if further than that from every side
    interior = np.all((c > 0.5 * side + 1e-9 * side) & (c < np.array(box) - 0.5 * side - 1e-9 * side), axis=1)
    assert interior.sum() == 4 * (n - 1) ** 3  # every centre but those a quarter cell from a side
    facet_area = math.sqrt(2) * a * a / 4
    volume = a ** 3 / math.sqrt(2)
    dirs = np.array([v for v in itertools.product((-1, 0, 1), repeat=3) if np.abs(v).sum() == 2]) / math.sqrt(2)
    assert len(dirs) == 12
    for k in np.flatnonzero(interior):
        idx, sgn = facets_of(res, k)
        assert len(idx) == 12
        assert np.all(np.abs(res["area"][idx] - facet_area) <= LATTICE_REL * facet_area)
        normals = res["normal"][idx] * sgn[:, None]
        # the twelve nearest-neighbour directions, each once
        match = np.abs(normals @ dirs.T - 1) <= LATTICE_REL
        assert np.array_equal(match.sum(axis=0), np.ones(12)) and np.array_equal(match.sum(axis=1), np.ones(12))
        nb = np.where(res["i"][idx] == k, res["j"][idx], res["i"][idx])
        assert np.all(np.abs(np.linalg.norm(c[nb] - c[k], axis=1) - a) <= LATTICE_REL * a)
        assert abs(res["cell_volume"][k] - volume) <= LATTICE_REL * volume
        assert np.all(res["box_area"][k] == 0)
    check_tiling(res, box, LATTICE_REL)
    check_on_power_diagram(res, c, r, box, POWER_REL)
    assert res["stats"]["cap_sorts"] == 0


@pytest.mark.parametrize("a,dims", [(1.0, (4, 4, 4)), (0.73, (5, 3, 4))])
def test_simple_cubic_cells_are_cubes(a, dims):
    c, box = simple_cubic(a, *dims)
    r = np.full(len(c), 0.5 * a)
    res = laguerre(c, r, box)
    nx, ny, nz = dims
    # every cell, at the box or not, is the cube of side a around its centre
    assert np.all(np.abs(res["cell_volume"] - a ** 3) <= LATTICE_REL * a ** 3)
    assert np.all(np.abs(res["area"] - a * a) <= LATTICE_REL * a * a)
    assert len(res["area"]) == (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1)
    assert np.all(np.abs(np.linalg.norm(c[res["j"]] - c[res["i"]], axis=1) - a) <= LATTICE_REL * a)
    interior = np.all((c > a) & (c < np.array(box) - a), axis=1)
    assert interior.any()
    for k in np.flatnonzero(interior):
        assert len(facets_of(res, k)[0]) == 6
    # a sphere at a side has a square piece of it, the others none
    at_side = np.stack([c[:, 0] < a, c[:, 0] > box[0] - a, c[:, 1] < a, c[:, 1] > box[1] - a,
                        c[:, 2] < a, c[:, 2] > box[2] - a], axis=1)
    assert np.all(np.abs(res["box_area"] - a * a * at_side) <= LATTICE_REL * a * a)
    check_tiling(res, box, LATTICE_REL)
    check_on_power_diagram(res, c, r, box, POWER_REL)
    # the diagonal neighbours of the triangulation touch along an edge or a corner: no facet
    assert res["stats"]["zero_area_pairs"] == res["stats"]["neighbour_pairs"] - len(res["area"]) > 0


@pytest.mark.parametrize("lattice", ["fcc", "sc"])
@pytest.mark.parametrize("jitter", [1e-15, 1e-13, 1e-11, 1e-10, 1e-8, 1e-4])
def test_nearly_degenerate_lattices_still_tile(lattice, jitter):
    # Centres and radii moved by up to `jitter` (relative): vertices of 4 or more cells split
    # into clusters at distances near the library's on-plane band (1e-11 of a cell's radius).
    # Measured: tiling and closure within 1.2e-11, vertices on the diagram within 2.1e-10 of
    # spacing^2 (the band's own size), no clip ordered by angle.
    c, box = fcc_lattice(1.0, 4) if lattice == "fcc" else simple_cubic(1.0, 6, 6, 6)
    rng = np.random.default_rng(0)
    c = np.clip(c + rng.uniform(-jitter, jitter, c.shape), 0, box)
    r = 0.5 * (1 + rng.uniform(-jitter, jitter, len(c)))
    res = laguerre(c, r, box)
    assert res["stats"]["cap_sorts"] == 0 and res["stats"]["empty_cells"] == 0
    check_tiling(res, box, RANDOM_REL)
    check_on_power_diagram(res, c, r, box, 1e-8)


def test_two_spheres_radical_plane():
    # The facet of two spheres lies on their radical plane, at (d^2 + r1^2 - r2^2) / 2d from the first.
    W, H, D = 3.0, 1.3, 0.9
    c = np.array([[0.7, 0.6, 0.4], [2.1, 0.6, 0.4]])
    r = np.array([0.55, 0.3])
    d = 1.4
    xp = 0.7 + (d * d + r[0] ** 2 - r[1] ** 2) / (2 * d)
    res = laguerre(c, r, (W, H, D))
    assert res["i"].tolist() == [0] and res["j"].tolist() == [1]
    assert res["area"][0] == pytest.approx(H * D, rel=LATTICE_REL)
    assert res["normal"][0] == pytest.approx([1, 0, 0], abs=LATTICE_REL)
    assert res["centroid"][0] == pytest.approx([xp, H / 2, D / 2], rel=LATTICE_REL)
    assert res["cell_volume"] == pytest.approx([xp * H * D, (W - xp) * H * D], rel=LATTICE_REL)
    assert res["box_area"][0] == pytest.approx([H * D, 0, xp * D, xp * D, xp * H, xp * H], rel=LATTICE_REL)


# --------------------------------------------------------------------------- random packings


@pytest.mark.parametrize("box,seed", [((6.0, 5.5, 5.0), 1), ((5.0, 5.0, 5.0), 2), ((6.0, 6.0, 4.0), 3)])
def test_random_packing_tiles_box_and_closes_cells(box, seed):
    c, r = random_spheres(np.random.default_rng(seed), 400, box)
    assert len(r) >= 150
    res = laguerre(c, r, box)
    st = res["stats"]
    assert st["hidden"] == 0 and st["empty_cells"] == 0 and st["dimension"] == 3 and st["cap_sorts"] == 0
    assert np.all(res["cell_volume"] > 0)
    # non-overlapping spheres: each lies inside its own cell, so its cell is larger than it
    assert np.all(res["cell_volume"] > 4 / 3 * np.pi * r ** 3)
    assert np.all(res["i"] < res["j"])
    assert np.all(np.diff(res["i"].astype(np.int64) * len(r) + res["j"]) > 0)
    check_tiling(res, box, RANDOM_REL)
    check_on_power_diagram(res, c, r, box, POWER_REL)
    scale2 = (np.prod(box) / len(r)) ** (2 / 3)
    assert st["max_asymmetry"] <= POWER_REL * scale2


def test_overlapping_spheres_hidden_and_empty_cells():
    # Heavily overlapping spheres of very different sizes: some are hidden, some cells leave
    # their centre; the cells still tile the box.
    rng = np.random.default_rng(5)
    box = (4.0, 3.0, 5.0)
    n = 300
    c = rng.uniform(0, 1, (n, 3)) * box
    r = rng.uniform(0.05, 1.2, n)
    res = laguerre(c, r, box)
    st = res["stats"]
    assert st["hidden"] > 0 and st["empty_cells"] >= st["hidden"]
    check_tiling(res, box, RANDOM_REL)
    check_on_power_diagram(res, c, r, box, POWER_REL)


def test_degenerate_sets():
    # one layer (coplanar centres: a 2D triangulation), one sphere, none, and a sphere inside another
    c, box = simple_cubic(1.0, 4, 3, 1)
    res = laguerre(c, np.full(len(c), 0.5), box)
    assert res["stats"]["dimension"] == 2
    assert np.allclose(res["cell_volume"], 1.0, rtol=LATTICE_REL) and len(res["area"]) == 3 * 3 + 4 * 2
    one = laguerre(np.array([[0.5, 0.5, 0.5]]), np.array([0.2]), (2.0, 3.0, 1.5))
    assert one["cell_volume"][0] == pytest.approx(9.0) and len(one["area"]) == 0
    assert one["box_area"][0] == pytest.approx([4.5, 4.5, 3.0, 3.0, 6.0, 6.0])
    none = laguerre(np.empty((0, 3)), np.empty(0), (1.0, 1.0, 1.0))
    assert len(none["cell_volume"]) == 0 and len(none["area"]) == 0
    same = laguerre(np.array([[0.5, 0.5, 0.5], [0.5, 0.5, 0.5]]), np.array([0.2, 0.3]), (1.0, 1.0, 1.0))
    assert same["cell_volume"].tolist() == [0.0, 1.0] and same["stats"]["hidden"] == 1


def test_without_polygons_same_facets():
    c, r = random_spheres(np.random.default_rng(7), 60, (4.0, 4.0, 4.0))
    a = laguerre(c, r, (4.0, 4.0, 4.0))
    b = laguerre(c, r, (4.0, 4.0, 4.0), polygons=False)
    assert "polygon_vertices" not in b
    for k in ("cell_volume", "box_area", "i", "j", "area", "normal", "centroid"):
        assert np.array_equal(a[k], b[k])


# --------------------------------------------------------------------------- bad input


def _call(**over):
    args = dict(x=[0.5, 1.5], y=[0.5, 0.5], z=[0.5, 0.5], r=[0.4, 0.4], width=2.0, height=1.0, depth=1.0)
    args.update(over)
    return _geom.laguerre_box(**args)


@pytest.mark.parametrize("over,words", [
    (dict(width=0.0), r"width W = 0 must be finite and > 0"),
    (dict(height=-1.0), r"height H = -1 must be finite and > 0"),
    (dict(depth=math.inf), r"depth D = inf must be finite and > 0"),
    (dict(depth=math.nan), r"depth D = nan"),
    (dict(r=[0.4, 0.0]), r"r\[1\] = 0 must be finite and > 0"),
    (dict(r=[-0.1, 0.4]), r"r\[0\] = -0.1 must be finite and > 0"),
    (dict(r=[0.4, math.nan]), r"r\[1\] = nan"),
    (dict(x=[0.5, math.nan]), r"x\[1\] = nan must be finite"),
    (dict(y=[math.inf, 0.5]), r"y\[0\] = inf must be finite"),
    (dict(x=[0.5, 2.5]), r"x\[1\] = 2.5 is outside the box: must be in \[0, W\] = \[0, 2\]"),
    (dict(z=[-0.01, 0.5]), r"z\[0\] = -0.01 is outside the box: must be in \[0, D\] = \[0, 1\]"),
    (dict(y=[0.5, 1.0000001]), r"y\[1\] = 1.0000001 is outside the box"),
])
def test_bad_input_refused(over, words):
    with pytest.raises(_geom.GeometryLibraryError, match=r"^swd_laguerre_box: " + words):
        _call(**over)


def test_size_mismatch_refused():
    with pytest.raises(ValueError, match=r"same length \(got 2, 2, 1, 2\)"):
        _call(z=[0.5])
    with pytest.raises(ValueError, match="1-D"):
        _call(r=[[0.4, 0.4]])


def test_capacity_too_small_reports_what_is_needed():
    # The C entry's contract the binding relies on to call again: -1, the error, and `needed`.
    import ctypes
    c, box = simple_cubic(1.0, 3, 2, 2)
    r = np.full(len(c), 0.5)
    full = laguerre(c, r, box)
    x, y, z = (np.ascontiguousarray(c[:, k]) for k in range(3))
    L = _geom._LONG
    fi, fj = np.empty(1, np.int32), np.empty(1, np.int32)
    fa, fn, fc = np.empty(1), np.empty(3), np.empty(3)
    fo, fv = np.empty(2, L), np.empty(3)
    vol, ba, needed = np.empty(len(r)), np.empty(6 * len(r)), np.zeros(2, L)
    ip, lp = ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_long)
    p = _geom._ptr
    m = _geom.lib().swd_laguerre_box(len(r), p(x), p(y), p(z), p(r), *box, 1, 1, p(fi, ip), p(fj, ip), p(fa), p(fn),
                                     p(fc), p(fo, lp), p(fv), p(vol), p(ba), p(needed, lp), None)
    assert m == -1
    assert _geom.lib().swd_geom_last_error().decode() == f"swd_laguerre_box: capacity 1 < {len(full['area'])} facets"
    assert needed.tolist() == [len(full["area"]), len(full["polygon_vertices"])]


def test_binding_calls_again_with_enough_room(monkeypatch):
    c, r = random_spheres(np.random.default_rng(4), 80, (4.0, 4.0, 4.0))
    full = laguerre(c, r, (4.0, 4.0, 4.0))
    monkeypatch.setattr(_geom, "_FACETS_PER_SPHERE_GUESS", 0)
    again = laguerre(c, r, (4.0, 4.0, 4.0))
    assert len(again["area"]) == len(full["area"]) > 64
    for k in ("area", "polygon_offset", "polygon_vertices", "box_area"):
        assert np.array_equal(again[k], full[k])
