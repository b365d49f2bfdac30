# SPDX-License-Identifier: GPL-2.0-or-later
"""Tests of the polyhedral aggregates (swelldem.meso.aggregates3d): widths against closed forms and
a brute-force search over directions, the shapes' size and elongation, the grading, and the
placement checked by an exact distance computed here (a quadratic programme over the two hulls'
vertex weights), not by the placement's own separating-axis test. Plain Python, about 20 s."""
import numpy as np
import pytest
from scipy.optimize import minimize
from scipy.spatial import ConvexHull

from swelldem import meso
from swelldem.meso import aggregates3d as A
from swelldem.meso.generator import seed_streams

TETRA = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=float)
CUBE = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], dtype=float)
OCTA = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)


def brute_width(v, n=20_000, seed=0):
    """The smallest width over a random grid of directions, each of the 10 best refined by a local search."""
    def width(angles):
        t, f = angles
        d = np.array([np.sin(t) * np.cos(f), np.sin(t) * np.sin(f), np.cos(t)])
        p = v @ d
        return p.max() - p.min()

    d = np.random.default_rng(seed).normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    p = v @ d.T
    w = p.max(axis=0) - p.min(axis=0)
    best = np.inf
    for k in np.argsort(w)[:10]:
        start = (np.arccos(np.clip(d[k, 2], -1, 1)), np.arctan2(d[k, 1], d[k, 0]))
        r = minimize(width, start, method="Nelder-Mead", options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 4000})
        best = min(best, r.fun)
    return float(best)


def hull_distance(P, Q):
    """Exact distance between the convex hulls of P and Q: min |P^T a - Q^T b|, a, b on simplices."""
    m, n = len(P), len(Q)

    def f(w):
        g = P.T @ w[:m] - Q.T @ w[m:]
        return g @ g

    def jac(w):
        g = P.T @ w[:m] - Q.T @ w[m:]
        return np.concatenate([2 * P @ g, -2 * Q @ g])

    cons = [{"type": "eq", "fun": lambda w: w[:m].sum() - 1}, {"type": "eq", "fun": lambda w: w[m:].sum() - 1}]
    w0 = np.concatenate([np.full(m, 1 / m), np.full(n, 1 / n)])
    r = minimize(f, w0, jac=jac, bounds=[(0, 1)] * (m + n), constraints=cons, method="SLSQP",
                 options={"ftol": 1e-14, "maxiter": 500})
    return float(np.sqrt(max(r.fun, 0.0)))


def params(**kw):
    base = dict(dim=3, width_mm=16.0, height_mm=16.0, depth_mm=16.0, sieve_fractions_mm=((2.4, 4.75),),
                fraction_shares=(1.0,), aggregate_area_fraction=0.25)
    return meso.MesoParameters(**dict(base, **kw)).validate()


# ---------------------------------------------------------------------------- shapes

@pytest.mark.parametrize("v, width", [
    (CUBE, 1.0),                   # face to face
    (OCTA, 2 / np.sqrt(3)),        # face to opposite face
    (TETRA, 2.0),                  # edge to opposite edge: a face-normal search alone gives 4 / sqrt(3)
])
def test_smallest_width_of_regular_solids(v, width):
    assert A.smallest_width(v)[0] == pytest.approx(width, rel=1e-12)


def test_smallest_width_is_the_minimum_over_all_directions():
    rng = np.random.default_rng(3)
    for _ in range(5):
        v = rng.normal(size=(15, 3)) * (1.0, 1.6, 0.7)
        w, axis = A.smallest_width(v)
        p = v @ axis
        assert p.max() - p.min() == pytest.approx(w, rel=1e-12)
        brute = brute_width(v)
        # no direction is narrower, and a search over all directions finds the same minimum
        assert w <= brute * (1 + 1e-12) and brute == pytest.approx(w, rel=1e-7)


@pytest.mark.parametrize("aspect", [1.5, 1.8, 2.5])
def test_a_drawn_polyhedron_has_its_sieve_size_and_elongation(aspect):
    rng = np.random.default_rng(7)
    for n in (6, 10):
        v, measured = A.random_polyhedron(rng, 3.5, aspect, n, 0.5)
        assert A.smallest_width(v)[0] == pytest.approx(3.5, rel=1e-9)
        length = max(np.linalg.norm(a - b) for a in v for b in v)
        assert measured == pytest.approx(length / 3.5, rel=1e-9) == pytest.approx(aspect, rel=2e-3)
        assert len(v) <= A.points_for(n)
        assert np.allclose(v.mean(axis=0), 0, atol=1.0)  # centred on its volume centroid, near the vertices' mean
        h = ConvexHull(v)
        assert np.all(h.equations[:, 3] < 0)  # the centroid is inside


def test_a_regular_polyhedron_approaches_the_sphere_of_its_width():
    sphere = np.pi / 6 * 2.0 ** 3
    ratio = [ConvexHull(A.random_polyhedron(np.random.default_rng(1), 2.0, 1.0, n, 0.0)[0]).volume / sphere
             for n in (10, 16)]
    # a hull of points on a sphere, scaled to the sphere's diameter as its smallest width, is a little
    # larger than the sphere (its width is below its circumradius x 2): 1.049 at 32 points, 1.036 at 81
    assert 1.0 < ratio[1] < ratio[0] < 1.06


def test_points_carry_the_2d_angular_spacing():
    assert [A.points_for(n) for n in (3, 6, 10, 16)] == [4, 11, 32, 81]
    with pytest.raises(meso.MesoParameterError, match=r"vertices_range = \(6, 17\) is out of range; allowed: .* <= 16 in 3D"):
        params(vertices_range=(6, 17))
    meso.MesoParameters(vertices_range=(6, 17)).validate()  # 2D keeps its 64


# ---------------------------------------------------------------------------- grading and placement

def test_the_grading_reaches_its_volume_with_each_fraction_its_share():
    p = params(width_mm=30.0, height_mm=30.0, depth_mm=30.0, sieve_fractions_mm=((2.4, 4.75), (4.75, 10.0)),
               fraction_shares=(0.4, 0.6), aggregate_area_fraction=0.35)
    aggs = A.draw_polyhedra(p, seed_streams(1)[0])
    vol = np.array([a.volume for a in aggs])
    frac = np.array([a.fraction for a in aggs])
    total = 0.35 * 30 ** 3
    finest = max(vol[frac == 0])
    assert abs(vol.sum() - total) <= 0.5 * finest  # the finest fraction closes the total
    shares = [vol[frac == k].sum() / vol.sum() for k in (0, 1)]
    assert shares == pytest.approx([0.4, 0.6], abs=0.02)  # one coarse grain is up to 0.02 of it
    assert all(lo <= a.sieve_size <= hi for a in aggs for lo, hi in [p.sieve_fractions_mm[a.fraction]])


@pytest.fixture(scope="module")
def placed():
    p = params()
    rng = seed_streams(2)[0]
    return p, A.place_polyhedra(p, A.draw_polyhedra(p, rng), rng, seed=2)


def test_placed_polyhedra_keep_the_gaps(placed):
    p, aggs = placed
    size = np.array([p.width_mm, p.height_mm, p.depth_mm])
    for a in aggs:
        assert np.all(a.vertices.min(axis=0) >= p.wall_gap_mm - 1e-12)
        assert np.all(a.vertices.max(axis=0) <= size - p.wall_gap_mm + 1e-12)
    close = 0
    for i in range(len(aggs)):
        for j in range(i + 1, len(aggs)):
            P, Q = aggs[i].vertices, aggs[j].vertices
            ci, cj = P.mean(axis=0), Q.mean(axis=0)
            reach = np.linalg.norm(P - ci, axis=1).max() + np.linalg.norm(Q - cj, axis=1).max()
            if np.linalg.norm(ci - cj) > reach + p.min_gap_mm:
                continue
            close += 1
            assert hull_distance(P, Q) >= p.min_gap_mm - 1e-6, (i, j)
    assert close > 5  # the check met pairs near each other


def test_the_same_seed_places_the_same_polyhedra(placed):
    p, aggs = placed
    rng = seed_streams(2)[0]
    again = A.place_polyhedra(p, A.draw_polyhedra(p, rng), rng, seed=2)
    assert len(again) == len(aggs) and all(np.array_equal(a.vertices, b.vertices) for a, b in zip(aggs, again))


def test_a_box_too_small_is_refused_with_its_size_and_seed():
    p = params(width_mm=8.0, height_mm=8.0, depth_mm=8.0, aggregate_area_fraction=0.5, max_placement_attempts=200)
    rng = np.random.default_rng(5)
    with pytest.raises(A.AggregatePlacementError) as ei:
        A.place_polyhedra(p, A.draw_polyhedra(p, rng), rng, seed=5)
    msg = str(ei.value)
    assert msg.startswith("swelldem: the aggregates do not fit the 8 x 8 x 8 mm box, seed 5: ")
    assert f"from a {A.MIN_RELIABLE_SIZE_3D_MM:g} mm cube on" in msg


def test_label_rule_inside_keeps_only_whole_spheres():
    cube = A.Polyhedron(CUBE * 4.0, 4.0, 0, 1.0)
    x = np.array([2.0, 0.3, 2.0, 5.0])
    r = np.array([0.5, 0.5, 1.99, 0.1])
    y = z = np.full(4, 2.0)
    assert A.label_spheres(x, y, z, r, [cube], "centre").tolist() == [0, 0, 0, -1]
    assert A.label_spheres(x, y, z, r, [cube], "inside").tolist() == [0, -1, 0, -1]
