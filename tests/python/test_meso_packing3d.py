# SPDX-License-Identifier: GPL-2.0-or-later
"""Tests of the 3D sphere packing (_geom.pack_box), checked here independently of the library's
own final check, and of the power cells (_geom.laguerre_box) made on it.

Needs the library built (SWELLDEM_BUILD_DIR or <repo>/build): a missing library is a failure.
Boxes of 3 to 5 mm (50 to 250 spheres), a few seconds in all.

Density bounds from the values measured on this machine (RelWithDebInfo, x86-64, GCC 12), seeds
1-3: 3 mm cube 0.483-0.496, 4 x 5 x 3 mm 0.522-0.534, 5 mm cube 0.550-0.555 (walls loosen small
boxes; 0.58-0.60 from 10 mm on, bench_packing3d.py); the bounds sit 0.03-0.04 below the lowest.
"""
import numpy as np
import pytest

from swelldem.meso import _geom  # conftest puts py/ on the path

RMAX = 0.48
RMIN = 0.32
BOXES = [(3.0, 3.0, 3.0), (4.0, 5.0, 3.0), (5.0, 5.0, 5.0)]
MIN_DENSITY = {BOXES[0]: 0.44, BOXES[1]: 0.49, BOXES[2]: 0.52}


@pytest.fixture(scope="module", params=[(b, s) for b in BOXES for s in (1, 2)], ids=lambda p: f"{p[0]}-seed{p[1]}")
def packed(request):
    box, seed = request.param
    x, y, z, r, st = _geom.pack_box(*box, RMIN, RMAX, seed)
    return box, seed, np.stack([x, y, z], axis=1), r, st


def gaps(c, r):
    """Surface gap of every pair i < j (brute force)."""
    d = np.sqrt(np.sum((c[:, None, :] - c[None, :, :]) ** 2, axis=-1))
    g = d - r[:, None] - r[None, :]
    return g[np.triu_indices(len(r), 1)]


def morton_keys(c, cell):
    """Z-curve index of the cubic cells of side `cell` holding the centres (x in the lowest bit)."""
    g = np.floor(c / cell).astype(np.uint64)
    key = np.zeros(len(c), dtype=np.uint64)
    for b in range(21):
        for a in range(3):
            key |= ((g[:, a] >> np.uint64(b)) & np.uint64(1)) << np.uint64(3 * b + a)
    return key


def test_no_overlap_inside_box_radii_in_bounds(packed):
    box, _, c, r, st = packed
    assert len(r) == st["n"] > 20
    assert np.all(gaps(c, r) >= -1e-9 * RMAX)
    assert np.all(c - r[:, None] >= -1e-12 * RMAX) and np.all(np.asarray(box) - c - r[:, None] >= -1e-12 * RMAX)
    assert np.all((r >= RMIN) & (r <= RMAX))
    assert st["max_overlap_rel"] <= 1e-9


def test_density_and_stats(packed):
    box, _, c, r, st = packed
    density = np.sum(4 / 3 * np.pi * r ** 3) / np.prod(box)
    assert density == pytest.approx(st["density"], rel=1e-12)
    assert density >= MIN_DENSITY[box]
    assert st["target_density"] >= density and st["sweeps"] > 0 and st["removed"] >= 0
    assert st["near_contacts_per_sphere"] >= 1.5  # measured 1.65-2.43


def test_compact_near_contacts(packed):
    """Most spheres touch (within 2.5 % of rmax) a neighbour or a side: no loose rattlers left."""
    box, _, c, r, _ = packed
    g = np.sqrt(np.sum((c[:, None, :] - c[None, :, :]) ** 2, axis=-1)) - r[:, None] - r[None, :]
    np.fill_diagonal(g, np.inf)
    wall = np.minimum(c - r[:, None], np.asarray(box) - c - r[:, None]).min(axis=1)
    near = np.minimum(g.min(axis=1), wall) <= 0.025 * RMAX
    assert near.mean() >= 0.9


def test_morton_order(packed):
    _, _, c, r, _ = packed
    key = morton_keys(c, RMIN)
    assert np.all(np.diff(key.astype(np.int64)) > 0)  # strictly increasing: one centre a cell at most


def test_numbering_puts_touching_partners_close():
    box = (5.0, 5.0, 5.0)
    x, y, z, r, _ = _geom.pack_box(*box, RMIN, RMAX, 1)
    c = np.stack([x, y, z], axis=1)
    g = np.sqrt(np.sum((c[:, None, :] - c[None, :, :]) ** 2, axis=-1)) - r[:, None] - r[None, :]
    i, j = np.nonzero(np.triu(g <= 0.025 * RMAX, 1))
    d = np.abs(i - j)
    rng = np.random.default_rng(0)
    shuffled = np.abs(rng.permutation(len(r))[i] - rng.permutation(len(r))[j])
    assert np.median(d) <= 0.3 * np.median(shuffled)


def test_seed_reproducible_and_distinct():
    a = _geom.pack_box(4.0, 5.0, 3.0, RMIN, RMAX, 7)
    b = _geom.pack_box(4.0, 5.0, 3.0, RMIN, RMAX, 7)
    c = _geom.pack_box(4.0, 5.0, 3.0, RMIN, RMAX, 8)
    for u, v in zip(a[:4], b[:4]):
        assert np.array_equal(u, v)
    assert a[4] == b[4]
    assert len(a[3]) != len(c[3]) or not np.array_equal(a[0], c[0])


@pytest.mark.parametrize("args,name", [
    ((0.0, 4, 4, RMIN, RMAX), "width"), ((4, -1, 4, RMIN, RMAX), "height"), ((4, 4, float("nan"), RMIN, RMAX), "depth"),
    ((4, 4, 4, 0.0, RMAX), "rmin"), ((4, 4, 4, 0.5, RMAX), "rmin"), ((4, 4, 4, RMIN, float("inf")), "rmax"),
    ((4, 4, 0.9, RMIN, RMAX), "rmax"), ((1e6, 1e6, 1e6, RMIN, RMAX), "width / rmin"),
    ((2000, 2000, 2000, RMIN, RMAX), "too many spheres"),
])
def test_bad_input_refused_naming_the_parameter(args, name):
    with pytest.raises(_geom.GeometryLibraryError, match=f"^swd_pack_box: {name}"):
        _geom.pack_box(*args, 1)


def test_bad_seed_refused():
    with pytest.raises(ValueError, match="seed"):
        _geom.pack_box(4, 4, 4, RMIN, RMAX, -1)


def test_power_cells_tile_the_box_and_every_sphere_has_one(packed):
    box, _, c, r, _ = packed
    res = _geom.laguerre_box(c[:, 0], c[:, 1], c[:, 2], r, *box, polygons=False)
    vol = np.prod(box)
    assert abs(res["cell_volume"].sum() - vol) <= 1e-9 * vol
    assert res["stats"]["hidden"] == 0 and res["stats"]["empty_cells"] == 0
    assert np.all(res["cell_volume"] > 0)
    # every sphere lies in its own cell: a cell is larger than its sphere
    assert np.all(res["cell_volume"] >= 4 / 3 * np.pi * r ** 3)
    st = res["stats"]
    positive = len(res["i"]) / st["neighbour_pairs"]
    per_sphere = 2 * len(res["i"]) / len(r)
    print(f"{box}: {len(r)} spheres, facets {len(res['i'])} of {st['neighbour_pairs']} neighbour pairs "
          f"({positive:.3f} positive), {per_sphere:.2f} facets a sphere")
    assert positive >= 0.7  # measured 0.77-0.84: the others are neighbours whose facet the box cuts away
    assert per_sphere >= 7  # interior cells have about 14; the box sides take the rest's share


def test_facets_per_interior_sphere_about_14():
    box = (5.0, 5.0, 5.0)
    x, y, z, r, _ = _geom.pack_box(*box, RMIN, RMAX, 3)
    res = _geom.laguerre_box(x, y, z, r, *box, polygons=False)
    count = np.bincount(np.concatenate([res["i"], res["j"]]), minlength=len(r))
    interior = res["box_area"].sum(axis=1) == 0
    mean = count[interior].mean()
    print(f"{interior.sum()} interior spheres of {len(r)}: {mean:.2f} facets each")
    assert interior.sum() >= 20 and 12 <= mean <= 16
