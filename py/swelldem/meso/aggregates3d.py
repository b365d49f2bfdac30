# SPDX-License-Identifier: GPL-2.0-or-later
"""Random convex polyhedron aggregates and their placement in a box (lengths in mm here).

The 2D generator's shape controls (swelldem.meso.aggregates), one dimension up:

- **Vertices**: ``vertices_range`` gives the vertex count n of the 2D polygon; a polyhedron gets
  V = round(n^2 / pi) points (n = 6 -> 11, n = 10 -> 32), the count that keeps the 2D angular spacing
  2 pi / n between neighbouring points on the sphere (4 pi / V = (2 pi / n)^2). The points sit on a
  randomly turned Fibonacci lattice of the unit sphere, each moved along the sphere by up to
  angularity x half the spacing in a random direction, at radii 1 +- 0.35 angularity (as in 2D);
  their convex hull is the shape.
- **Aspect ratio**: length / smallest width, the length being the longest chord. The hull is first
  made equally spread in its three principal directions (an affine map of its vertices), then
  stretched along a random direction until its aspect ratio reaches one drawn uniformly in
  ``aspect_ratio_range`` (a prolate grain, as 2D stretches a polygon along its length); a ratio
  below the equal-spread shape's own (1.1-1.4 at angularity 0.5: a polyhedron is not a sphere)
  leaves it unstretched, and the aspect ratio reached is the one stored.
- **Sieve size**: the smallest width, scaled to a size drawn uniformly in the fraction. For a
  prolate grain the two smaller widths are about equal, and a grain passes a square mesh of its
  smallest width in that orientation: the same definition as the 2D sieve size. The smallest width
  of a convex polytope is attained between a face and the vertex farthest from it, or between two
  edges (antipodal edge pairs); :func:`smallest_width` takes both.
- **Grading**: per fraction, coarsest first, polyhedra are drawn until their volume reaches
  share x aggregate_area_fraction x W H D (the volume fraction in 3D) plus what the coarser fractions
  missed or exceeded; the last one is kept only if it brings the total closer to the target.
- **Placement**: largest volume first, at uniformly random orientations and positions, rejected
  when closer than ``min_gap_mm`` to a placed polyhedron or ``wall_gap_mm`` to a face of the box.
  Two polyhedra are far enough apart when some axis separates their projections by at least the
  gap; the axes tried are both polyhedra's face normals and the cross products of their edges,
  which find a separating axis for every disjoint pair. A pair closer than the gap on every axis
  tried is rejected: this never accepts a pair closer than the gap, and rejects only pairs whose
  nearest features are a vertex and an edge or two vertices within a gap's distance of touching.
"""
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .aggregates import AggregatePlacementError

#: Smallest cube side [mm] at which the default grading (35 % by volume, 2.4-10 mm) placed its
#: aggregates for every seed tried (docs/mesostructure.md, "3D mesostructure").
MIN_RELIABLE_SIZE_3D_MM = 30.0


@dataclass
class Polyhedron:
    """One aggregate: hull vertices [mm] (absolute after placement), sieve size [mm], fraction index,
    measured length / smallest width [-]."""

    vertices: np.ndarray
    sieve_size: float
    fraction: int
    aspect_ratio: float

    # the vertices do not change once a polyhedron is made: its hull is computed once, for the grading,
    # the placement, the statistics and the labels alike
    @cached_property
    def _hull(self):
        return _hull(self.vertices)

    @property
    def volume(self):
        """[mm^3]"""
        return float(self._hull.volume)

    @property
    def equations(self):
        """Hull half-spaces (k, 4): n . x + c <= 0 inside, n unit outward."""
        return self._hull.equations


def _hull(points):
    from scipy.spatial import ConvexHull
    return ConvexHull(points)


def _unique_normals(eq, tol=1e-9):
    """Face normals of a hull's equations with the coplanar triangles' duplicates removed."""
    n = eq[:, :3]
    same = np.triu(n @ n.T > 1.0 - tol, 1)
    return n[~same.any(axis=0)]


def _edges(hull):
    """Unit directions of the hull's edges (triangle sides between faces of different planes)."""
    tri = hull.simplices
    pairs = {}
    for t, (a, b, c) in enumerate(tri):
        for e in ((a, b), (b, c), (c, a)):
            pairs.setdefault(tuple(sorted(e)), []).append(t)
    n = hull.equations[:, :3]
    e = [k for k, ts in pairs.items() if len(ts) == 2 and n[ts[0]] @ n[ts[1]] < 1.0 - 1e-9]
    v = hull.points[np.array(e)]
    d = v[:, 1] - v[:, 0]
    return d / np.linalg.norm(d, axis=1)[:, None]


def smallest_width(vertices):
    """Smallest width of the convex hull of (n, 3) points, and the unit direction across it.

    Candidates: every face normal (face against its farthest vertex) and every cross product of two
    edge directions (edge against edge), which include the minimum of the width over all directions
    for a convex polytope."""
    h = _hull(vertices)
    pts = h.points[h.vertices]
    normals = _unique_normals(h.equations)
    ed = _edges(h)
    cand = [normals]
    if len(ed) > 1:
        c = np.cross(ed[:, None, :], ed[None, :, :]).reshape(-1, 3)
        ln = np.linalg.norm(c, axis=1)
        c = c[ln > 1e-9] / ln[ln > 1e-9][:, None]
        cand.append(c)
    axes = np.concatenate(cand)
    proj = pts @ axes.T
    w = proj.max(axis=0) - proj.min(axis=0)
    k = int(np.argmin(w))
    return float(w[k]), axes[k]


def _fibonacci_sphere(n):
    k = np.arange(n) + 0.5
    z = 1.0 - 2.0 * k / n
    phi = np.pi * (1.0 + 5 ** 0.5) * k
    s = np.sqrt(1.0 - z * z)
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1)


def random_rotation(rng):
    """A uniformly random rotation matrix (QR of a Gaussian matrix, signs fixed)."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def points_for(n_vertices):
    """Points on the sphere for a 2D vertex count n: round(n^2 / pi), at least 4."""
    return max(4, int(round(n_vertices * n_vertices / np.pi)))


def random_polyhedron(rng, size, aspect_ratio, n_vertices, angularity):
    """A convex polyhedron centred on its centroid, smallest width = size [mm], length / smallest width
    ~ aspect_ratio; returns (hull vertices (k, 3), measured aspect ratio)."""
    m = points_for(n_vertices)
    p = _fibonacci_sphere(m) @ random_rotation(rng).T
    spacing = np.sqrt(4.0 * np.pi / m)
    # a random tangent direction at each point, then a move along the sphere of up to angularity x spacing / 2
    t = rng.normal(size=(m, 3))
    t -= (t * p).sum(axis=1)[:, None] * p
    t /= np.linalg.norm(t, axis=1)[:, None]
    ang = angularity * 0.5 * spacing * rng.uniform(0.0, 1.0, m)
    p = np.cos(ang)[:, None] * p + np.sin(ang)[:, None] * t
    p *= (1.0 + 0.35 * angularity * rng.uniform(-1.0, 1.0, m))[:, None]
    v = p[_hull(p).vertices]
    # whiten: equal spread of the vertices in every principal direction, so that a stretch along one
    # random direction sets the elongation from a nearly isotropic start
    v = v - v.mean(axis=0)
    lam, vec = np.linalg.eigh(v.T @ v / len(v))
    v = v @ vec @ np.diag(1.0 / np.sqrt(lam)) @ vec.T
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)

    def stretched(t):
        return v + (t - 1.0) * np.outer(v @ axis, axis)

    def aspect(t):
        u = stretched(t)
        return _diameter(u)[0] / smallest_width(u)[0]

    t = 1.0
    if aspect(1.0) < aspect_ratio:
        lo, hi = 1.0, 2.0 * aspect_ratio
        for _ in range(30):
            t = 0.5 * (lo + hi)
            if abs(aspect(t) - aspect_ratio) < 1e-3 * aspect_ratio:
                break
            lo, hi = (t, hi) if aspect(t) < aspect_ratio else (lo, t)
    v = stretched(t)
    w, _ = smallest_width(v)
    measured = _diameter(v)[0] / w
    v = v * (size / w)
    h = _hull(v)
    v = h.points[h.vertices]
    return v - _centroid(h), float(measured)


def _diameter(v):
    """Longest chord of a point set: its length and unit direction."""
    d = v[:, None, :] - v[None, :, :]
    n = np.einsum("ijk,ijk->ij", d, d)
    i, j = np.unravel_index(int(np.argmax(n)), n.shape)
    L = float(np.sqrt(n[i, j]))
    return L, d[i, j] / L


def _centroid(h):
    """Volume centroid of a scipy ConvexHull (tetrahedra from one of its vertices; qhull does not orient
    its triangles alike, and every such tetrahedron of a convex hull has a volume >= 0)."""
    o = h.points[h.vertices[0]]
    tri = h.points[h.simplices]
    vol = np.abs(np.einsum("ij,ij->i", tri[:, 0] - o, np.cross(tri[:, 1] - o, tri[:, 2] - o))) / 6.0
    cen = (tri.sum(axis=1) + o) / 4.0
    return (vol[:, None] * cen).sum(axis=0) / vol.sum()


def draw_polyhedra(p, rng):
    """Polyhedra (centred at the origin) for every sieve fraction, per the grading of parameters p.

    The fractions are drawn coarsest first and each one's shortfall or excess is carried into the
    next one's target: one coarse grain is up to 2 % of a 30 mm cube, so per-fraction rounding alone
    would miss the total by that much, while the finest fraction's grains round it to about 0.2 %."""
    total = p.aggregate_area_fraction * p.width_mm * p.height_mm * p.depth_mm
    out = []
    if total <= 0:
        return out
    ar_lo, ar_hi = map(float, p.aspect_ratio_range)
    v_lo, v_hi = p.vertices_range
    fractions = list(enumerate(zip(p.sieve_fractions_mm, p.fraction_shares)))
    carry = 0.0
    for k, ((d_lo, d_hi), share) in sorted(fractions, key=lambda f: -f[1][0][1]):
        target = share * total + carry if share > 0 else 0.0
        acc = 0.0
        while acc < target:
            d = rng.uniform(d_lo, d_hi)
            ar = rng.uniform(ar_lo, ar_hi)
            nv = rng.integers(v_lo, v_hi + 1)
            v, ar_real = random_polyhedron(rng, d, ar, nv, p.angularity)
            grain = Polyhedron(v, float(d), k, ar_real)
            if acc + grain.volume > target and (acc + grain.volume - target) > (target - acc):
                break  # the total is closer to the target without this one
            out.append(grain)
            acc += grain.volume
        carry = target - acc
    return out


class _Shape:
    """What the placement tests of one orientation of a polyhedron need, relative to its centroid."""

    def __init__(self, v):
        h = _hull(v)
        self.v = h.points[h.vertices]
        self.normals = _unique_normals(h.equations)
        self.edges = _edges(h)
        self.eq = h.equations
        self.rho = float(np.linalg.norm(self.v, axis=1).max())       # bounding sphere
        self.inner = float(-h.equations[:, 3].max())                  # inscribed sphere about the centroid (origin)


def _far_enough(A, pa, B, pb, gap):
    """True when some axis (face normals of both, edge cross products) separates the translated
    polyhedra by at least gap; False otherwise (overlapping, or not shown to be gap apart)."""
    va, vb = A.v + pa, B.v + pb
    axes = [A.normals, B.normals]
    c = np.cross(A.edges[:, None, :], B.edges[None, :, :]).reshape(-1, 3)
    ln = np.linalg.norm(c, axis=1)
    ok = ln > 1e-9
    axes.append(c[ok] / ln[ok][:, None])
    ax = np.concatenate(axes)
    qa, qb = va @ ax.T, vb @ ax.T
    sep = np.maximum(qb.min(axis=0) - qa.max(axis=0), qa.min(axis=0) - qb.max(axis=0))
    return bool(sep.max() >= gap)


class _Clearance:
    """A voxel grid of the box holding, at each voxel centre, a lower bound of its distance to the
    placed polyhedra (the largest signed distance to a polyhedron's face planes, which never exceeds
    the true distance). A centroid can only go where that bound is at least the grain's inscribed
    radius plus the gap, so positions are drawn among those voxels: late, small grains find the
    last pockets of free space instead of missing them in thousands of uniform tries."""

    def __init__(self, size, h):
        self.h = h
        self.n = np.maximum(1, np.ceil(size / h).astype(int))
        self.d = np.full(tuple(self.n), np.inf)

    def add(self, shape, c, reach):
        """Lower the bound around a polyhedron placed at c, up to reach beyond its bounding sphere."""
        lo = np.maximum(0, np.floor((c - shape.rho - reach) / self.h).astype(int))
        hi = np.minimum(self.n, np.ceil((c + shape.rho + reach) / self.h).astype(int) + 1)
        if np.any(hi <= lo):
            return
        axes = [(np.arange(lo[k], hi[k]) + 0.5) * self.h - c[k] for k in range(3)]
        g = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        d = (g @ shape.eq[:, :3].T + shape.eq[:, 3]).max(axis=1)
        sub = self.d[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]]
        np.minimum(sub, d.reshape(sub.shape), out=sub)

    def candidates(self, need, lo, hi):
        """Flat indices of the voxels with clearance >= need whose centres lie in [lo, hi]."""
        i0 = np.maximum(0, np.ceil(lo / self.h - 0.5).astype(int))
        i1 = np.minimum(self.n, np.floor(hi / self.h - 0.5).astype(int) + 1)
        if np.any(i1 <= i0):
            return None, i0
        sub = self.d[i0[0]:i1[0], i0[1]:i1[1], i0[2]:i1[2]]
        return np.argwhere(sub >= need), i0


def place_polyhedra(p, aggs, rng, seed=None):
    """Place the polyhedra largest first; returns them with absolute vertices [mm] (in the order placed).
    seed: the generator's seed, named in the error when a polyhedron finds no place."""
    size = np.array([p.width_mm, p.height_mm, p.depth_mm], dtype=float)
    gap, wgap = float(p.min_gap_mm), float(p.wall_gap_mm)
    vols = [a.volume for a in aggs]
    order = sorted(range(len(aggs)), key=lambda k: -vols[k])
    placed, shapes, pos = [], [], np.zeros((len(aggs), 3))
    rho, inner = np.zeros(len(aggs)), np.zeros(len(aggs))
    grid = _Clearance(size, min(0.5, float(size.min()) / 40.0))
    reach = max((_Shape(a.vertices).rho for a in aggs), default=0.0) + gap
    for rank, k in enumerate(order):
        a = aggs[k]
        ok = False
        for _ in range(p.max_placement_attempts):
            s = _Shape(a.vertices @ random_rotation(rng).T)
            lo = wgap - s.v.min(axis=0)
            hi = size - wgap - s.v.max(axis=0)
            if np.any(hi < lo):
                continue  # this orientation does not fit between the faces
            m = len(placed)
            if m:
                free, i0 = grid.candidates(s.inner + gap, lo, hi)
                if free is None or len(free) == 0:
                    continue  # no room for this orientation's inscribed sphere
                v = free[rng.integers(len(free))] + i0
                c = np.clip((v + rng.uniform(0.0, 1.0, 3)) * grid.h, lo, hi)
                dist = np.linalg.norm(pos[:m] - c, axis=1)
                if np.any(dist < inner[:m] + s.inner):
                    continue  # the inscribed spheres overlap
                near = np.flatnonzero(dist < rho[:m] + s.rho + gap)
                if any(not _far_enough(shapes[q], pos[q], s, c, gap) for q in near):
                    continue
            else:
                c = rng.uniform(lo, hi)
            placed.append(Polyhedron(s.v + c, a.sieve_size, a.fraction, a.aspect_ratio))
            shapes.append(s)
            pos[len(placed) - 1], rho[len(placed) - 1], inner[len(placed) - 1] = c, s.rho, s.inner
            grid.add(s, c, reach)
            ok = True
            break
        if not ok:
            raise AggregatePlacementError(_placement_failure(p, vols, placed, rank, a, seed))
    return placed


def _placement_failure(p, vols, placed, rank, a, seed):
    box = f"{p.width_mm:g} x {p.height_mm:g} x {p.depth_mm:g}"
    V = p.width_mm * p.height_mm * p.depth_mm
    done = sum(q.volume for q in placed) / V
    seed_text = "" if seed is None else f", seed {seed}"
    return (f"swelldem: the aggregates do not fit the {box} mm box{seed_text}: aggregate {rank + 1} of {len(vols)} "
            f"(sieve size {a.sieve_size:.3g} mm) found no free position in max_placement_attempts = "
            f"{p.max_placement_attempts} random tries. The {len(vols)} drawn fill {100 * sum(vols) / V:.1f} % of the box "
            f"(aggregate_area_fraction = {p.aggregate_area_fraction:g}, the volume fraction in 3D); the {len(placed)} "
            f"placed fill {100 * done:.1f} %. With the default grading (sieve sizes up to 10 mm) every seed tried "
            f"places them from a {MIN_RELIABLE_SIZE_3D_MM:g} mm cube on (docs/mesostructure.md, '3D mesostructure'). "
            f"Use another seed, a larger box, or a lower aggregate_area_fraction, min_gap_mm or wall_gap_mm.")


def label_spheres(x, y, z, r, polyhedra, rule="centre"):
    """Aggregate index of every sphere (-1 mortar), lengths in one unit: rule "centre", the centre is
    inside the hull or on it; rule "inside", the whole sphere is inside it."""
    agg = np.full(len(x), -1, dtype=np.int32)
    c = np.stack([x, y, z], axis=1)
    for k, poly in enumerate(polyhedra):
        v = poly.vertices
        lo, hi = v.min(axis=0), v.max(axis=0)
        cand = np.flatnonzero(np.all((c >= lo) & (c <= hi), axis=1))
        if cand.size == 0:
            continue
        eq = poly.equations
        # signed distance to every face plane, negative inside
        sd = c[cand] @ eq[:, :3].T + eq[:, 3]
        outer = sd.max(axis=1)
        need = 0.0 if rule == "centre" else -r[cand]
        agg[cand[outer <= need]] = k
    return agg
