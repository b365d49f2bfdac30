# SPDX-License-Identifier: GPL-2.0-or-later
"""The numbering of swelldem.meso.generate (issue 13): order="hilbert" renumbers the discs along a
Hilbert curve and sorts the contacts by their discs; it must give exactly the discs, contacts and
Laguerre neighbours of order="packing" (the packing's own numbering, the default), only renumbered, and put the
two discs of a contact close in the numbering. Physics-free and deterministic.

Needs the geometry library built (SWELLDEM_BUILD_DIR or <repo>/build).
"""
import numpy as np
import pytest

from swelldem import meso  # conftest puts py/ on the path
from swelldem.meso import generator as genmod

SMALL = dict(width_mm=30.0, height_mm=25.0)


@pytest.fixture(scope="module")
def pair():
    return meso.generate(seed=3, **SMALL), meso.generate(seed=3, order="hilbert", **SMALL)


@pytest.mark.parametrize("bits", [1, 2, 3, 6])
def test_hilbert_index_visits_every_cell_once_through_neighbouring_cells(bits):
    n = 1 << bits
    gx, gy = (v.ravel() for v in np.meshgrid(np.arange(n), np.arange(n)))
    d = genmod._hilbert_index(gx, gy, bits)
    assert np.array_equal(np.sort(d), np.arange(n * n))  # a bijection of the grid onto 0 .. n^2 - 1
    o = np.argsort(d)
    steps = np.abs(np.diff(gx[o])) + np.abs(np.diff(gy[o]))
    assert np.all(steps == 1)  # a continuous curve: each cell's successor shares a side with it
    assert (gx[o[0]], gy[o[0]]) == (0, 0) and (gx[o[-1]], gy[o[-1]]) == (n - 1, 0)


def test_default_is_packing_and_recorded(pair):
    p, h = pair
    assert p.stats["order"] == "packing" and h.stats["order"] == "hilbert"
    with pytest.raises(meso.MesoParameterError, match="order"):
        meso.generate(seed=3, order="morton", **SMALL)


def _disc_map(p, h):
    """perm with h's disc k = p's disc perm[k], matched by exact centre coordinates."""
    where = {(x, y): k for k, (x, y) in enumerate(zip(p.x.tolist(), p.y.tolist()))}
    assert len(where) == p.n_particles  # centres are distinct
    return np.array([where[(x, y)] for x, y in zip(h.x.tolist(), h.y.tolist())])


def test_same_discs_contacts_and_neighbours_only_renumbered(pair):
    p, h = pair
    assert (h.n_particles, h.n_contacts, len(h.neighbours)) == (p.n_particles, p.n_contacts, len(p.neighbours))
    perm = _disc_map(p, h)
    assert np.array_equal(np.sort(perm), np.arange(p.n_particles))
    for k in ("x", "y", "r", "material", "aggregate_id", "cell_area_m2"):
        assert np.array_equal(getattr(h, k), getattr(p, k)[perm]), k
        assert getattr(h, k).dtype == getattr(p, k).dtype, k
    old = {}  # p's contacts keyed by their pair of discs, with every per-contact value
    for c, (i, j) in enumerate(p.contacts.tolist()):
        old[frozenset((i, j))] = (int(p.kind[c]), p.facet_length_m[c], p.facet_area_m2[c], p.distance_m[c], p.gap_m[c],
                                  tuple(p.facet_segment_m[c]))
    new = {}
    for c, (i, j) in enumerate(h.contacts.tolist()):
        new[frozenset((int(perm[i]), int(perm[j])))] = (int(h.kind[c]), h.facet_length_m[c], h.facet_area_m2[c], h.distance_m[c],
                                                         h.gap_m[c], tuple(h.facet_segment_m[c]))
    assert new == old
    nb_old = {frozenset(ij): L for ij, L in zip(map(tuple, p.neighbours.tolist()), p.neighbour_facet_length_m)}
    nb_new = {frozenset((int(perm[i]), int(perm[j]))): L for (i, j), L in zip(h.neighbours.tolist(), h.neighbour_facet_length_m)}
    assert nb_new == nb_old
    assert len(h.polygons) == len(p.polygons) and all(np.array_equal(a, b) for a, b in zip(h.polygons, p.polygons))
    for k in ("aggregate_sieve_size_m", "aggregate_fraction", "aggregate_aspect_ratio"):
        assert np.array_equal(getattr(h, k), getattr(p, k)), k
    sp = {k: v for k, v in p.stats.items() if k not in ("timings_s", "wall_s", "order")}
    sh = {k: v for k, v in h.stats.items() if k not in ("timings_s", "wall_s", "order")}
    assert sh == sp


def test_pairs_are_ordered_and_sorted(pair):
    _, h = pair
    for ij in (h.contacts, h.neighbours):
        assert ij.dtype == np.int32 and np.all(ij[:, 0] < ij[:, 1])
        key = ij[:, 0].astype(np.int64) * h.n_particles + ij[:, 1]
        assert np.all(np.diff(key) > 0)  # sorted by (i, j), no duplicate


def test_hilbert_numbering_puts_contact_partners_close(pair):
    p, h = pair
    dp = np.abs(p.contacts[:, 0].astype(np.int64) - p.contacts[:, 1])
    dh = np.abs(h.contacts[:, 0].astype(np.int64) - h.contacts[:, 1])
    # The packing's numbering goes layer by layer: a contact's partner one layer up is a layer of
    # discs away (about the specimen's width in discs, 25 here). Along the Hilbert curve most
    # partners are a few numbers away; a few sit across the curve's seams (the mean stays similar).
    assert np.median(dp) >= 15
    assert np.median(dh) <= 0.2 * np.median(dp)
    assert np.mean(dh <= 8) >= 0.6 and np.mean(dp <= 8) <= 0.4
