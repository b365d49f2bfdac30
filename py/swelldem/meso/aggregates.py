# SPDX-License-Identifier: GPL-2.0-or-later
"""Random convex polygon aggregates and their placement (lengths in mm here).

Shape: ``n`` vertices on a circle at angles 2 pi k / n jittered by up to
+-angularity/2 of their spacing, radii 1 +- 0.35 angularity, convex hull; then
the polygon is stretched along the direction of its smallest width until
length / width reaches a ratio drawn in ``aspect_ratio_range``, rotated at random
and scaled so that its smallest width (its 2D sieve size) equals the size drawn
uniformly in its sieve fraction.

Grading: for each fraction, polygons are drawn until their area reaches
share x aggregate_area_fraction x W H (the last one is kept only if that brings
the total closer to the target). Placement: all polygons, largest area first,
at uniformly random positions and orientations, rejected when closer than
``min_gap_mm`` to a placed polygon or ``wall_gap_mm`` to a specimen side.
"""
from dataclasses import dataclass

import numpy as np


#: Smallest square specimen side [mm] at which the default grading (sieve sizes up to 10 mm, 35 %
#: of the area) placed its aggregates for every seed tried: none of seeds 0-299 failed at 24, 25,
#: 26 and 28 mm, while 1 to 3 of 300 failed at 20 to 23 mm and about 1 in 4 at 14-15 mm
#: (docs/guide.md, "Specimen size"). Quoted in the placement error.
MIN_RELIABLE_SIZE_MM = 24.0


class AggregatePlacementError(ValueError, RuntimeError):
    """The aggregates drawn for a specimen could not all be placed: the specimen is too small for
    them with this seed, or the parameters are too demanding. A ValueError, as every swelldem
    refusal of its input, so that scripts report it as such (no traceback)."""


@dataclass
class Aggregate:
    """One aggregate: CCW vertices [mm] (absolute after placement), sieve size [mm], fraction index."""

    vertices: np.ndarray
    sieve_size: float
    fraction: int
    aspect_ratio: float

    @property
    def area(self):
        return polygon_area(self.vertices)


def polygon_area(v):
    """Signed area (positive for CCW) of a polygon given as (n, 2) vertices."""
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def convex_hull(points):
    """CCW convex hull (Andrew's monotone chain) of (n, 2) points, no repeated vertex."""
    pts = np.unique(np.asarray(points, dtype=float), axis=0)
    if len(pts) < 3:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(tuple(p))
    for p in pts[::-1]:
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(tuple(p))
    return np.array(lower[:-1] + upper[:-1])


def width_and_length(v):
    """Smallest width of a convex polygon, the unit direction across it, and the extent perpendicular to it."""
    e = np.roll(v, -1, axis=0) - v
    n = np.stack([e[:, 1], -e[:, 0]], axis=1)
    n /= np.linalg.norm(n, axis=1)[:, None]
    proj = v @ n.T  # (vertices, normals)
    widths = proj.max(axis=0) - proj.min(axis=0)
    k = int(np.argmin(widths))
    nk = n[k]
    t = np.array([-nk[1], nk[0]])
    pt = v @ t
    return float(widths[k]), nk, float(pt.max() - pt.min())


def random_polygon(rng, size, aspect_ratio, n_vertices, angularity):
    """A convex CCW polygon centred on its centroid, smallest width = size [mm], length/width ~ aspect_ratio."""
    n = int(n_vertices)
    spacing = 2 * np.pi / n
    ang = spacing * np.arange(n) + angularity * spacing * rng.uniform(-0.5, 0.5, n) + rng.uniform(0, 2 * np.pi)
    rad = 1.0 + 0.35 * angularity * rng.uniform(-1.0, 1.0, n)
    v = convex_hull(np.stack([rad * np.cos(ang), rad * np.sin(ang)], axis=1))
    for _ in range(6):
        w, nk, length = width_and_length(v)
        ratio = length / w
        if abs(ratio - aspect_ratio) < 1e-3 * aspect_ratio:
            break
        # stretch along the direction perpendicular to the smallest width
        t = np.array([-nk[1], nk[0]])
        f = aspect_ratio / ratio
        v = v + (f - 1.0) * np.outer(v @ t, t)
    w, nk, length = width_and_length(v)
    v = v * (size / w)
    c = _centroid(v)
    v = v - c
    theta = rng.uniform(0, 2 * np.pi)
    rot = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    return v @ rot.T, length / w


def _centroid(v):
    x, y = v[:, 0], v[:, 1]
    xs, ys = np.roll(x, -1), np.roll(y, -1)
    c = x * ys - xs * y
    a = 0.5 * c.sum()
    return np.array([((x + xs) * c).sum() / (6 * a), ((y + ys) * c).sum() / (6 * a)])


def draw_aggregates(p, rng):
    """Polygons (centred at the origin) for every sieve fraction, per the grading of parameters p."""
    total = p.aggregate_area_fraction * p.width_mm * p.height_mm
    out = []
    if total <= 0:
        return out
    ar_lo, ar_hi = map(float, p.aspect_ratio_range)
    v_lo, v_hi = p.vertices_range
    for k, ((d_lo, d_hi), share) in enumerate(zip(p.sieve_fractions_mm, p.fraction_shares)):
        target = share * total
        acc = 0.0
        while acc < target:
            d = rng.uniform(d_lo, d_hi)
            ar = rng.uniform(ar_lo, ar_hi)
            nv = rng.integers(v_lo, v_hi + 1)
            v, ar_real = random_polygon(rng, d, ar, nv, p.angularity)
            a = polygon_area(v)
            if acc + a > target and (acc + a - target) > (target - acc):
                break  # the total is closer to the target without this one
            out.append(Aggregate(v, float(d), k, float(ar_real)))
            acc += a
    return out


def _too_close(P, Q, gap):
    """True if convex CCW polygons P and Q overlap or are closer than gap."""
    best = -np.inf
    for A, B in ((P, Q), (Q, P)):
        e = np.roll(A, -1, axis=0) - A
        n = np.stack([e[:, 1], -e[:, 0]], axis=1)
        n /= np.linalg.norm(n, axis=1)[:, None]
        sep = (B @ n.T).min(axis=0) - (A * n).sum(axis=1)  # separation along each outward normal of A
        best = max(best, float(sep.max()))
    if best >= gap:
        return False  # a separating axis already shows the distance is >= gap
    if best <= 0:
        return True  # no separating axis: they intersect
    return _distance(P, Q) < gap


def _distance(P, Q):
    """Distance between two disjoint polygons: smallest vertex-edge distance."""
    d = np.inf
    for A, B in ((P, Q), (Q, P)):
        a = B
        b = np.roll(B, -1, axis=0)
        ab = b - a
        L2 = (ab * ab).sum(axis=1)
        for pt in A:
            t = np.clip(((pt - a) * ab).sum(axis=1) / L2, 0.0, 1.0)
            proj = a + t[:, None] * ab
            d = min(d, float(np.sqrt(((proj - pt) ** 2).sum(axis=1)).min()))
    return d


def place_aggregates(p, aggs, rng, seed=None):
    """Place the polygons largest first; returns them with absolute vertices [mm] (same order as
    placed). seed: the generator's seed, named in the error when a polygon finds no place."""
    W, H = p.width_mm, p.height_mm
    gap, wgap = p.min_gap_mm, p.wall_gap_mm
    order = sorted(range(len(aggs)), key=lambda k: -aggs[k].area)
    placed = []
    centres = np.zeros((len(aggs), 2))
    radii = np.zeros(len(aggs))
    for rank, k in enumerate(order):
        a = aggs[k]
        v0 = a.vertices
        ok = False
        for attempt in range(p.max_placement_attempts):
            theta = rng.uniform(0, 2 * np.pi)
            c, s = np.cos(theta), np.sin(theta)
            v = v0 @ np.array([[c, s], [-s, c]])
            lo = v.min(axis=0)
            hi = v.max(axis=0)
            xmin, xmax = wgap - lo[0], W - wgap - hi[0]
            ymin, ymax = wgap - lo[1], H - wgap - hi[1]
            if xmax < xmin or ymax < ymin:
                continue  # this orientation does not fit between the sides
            pos = np.array([rng.uniform(xmin, xmax), rng.uniform(ymin, ymax)])
            rho = float(np.sqrt((v * v).sum(axis=1)).max())
            m = len(placed)
            if m:
                dist = np.hypot(centres[:m, 0] - pos[0], centres[:m, 1] - pos[1])
                near = np.nonzero(dist < radii[:m] + rho + gap)[0]
                vv = v + pos
                if any(_too_close(vv, placed[q].vertices, gap) for q in near):
                    continue
            placed.append(Aggregate(v + pos, a.sieve_size, a.fraction, a.aspect_ratio))
            centres[len(placed) - 1] = pos
            radii[len(placed) - 1] = rho
            ok = True
            break
        if not ok:
            raise AggregatePlacementError(_placement_failure(p, aggs, placed, rank, a, seed))
    return placed


def _placement_failure(p, aggs, placed, rank, a, seed):
    """The message of an AggregatePlacementError: what failed, why a small specimen fails, what to do."""
    W, H = p.width_mm, p.height_mm
    drawn = sum(q.area for q in aggs) / (W * H)
    done = sum(q.area for q in placed) / (W * H)
    seed_text = "" if seed is None else f", seed {seed}"
    return (f"swelldem: the aggregates do not fit the {W:g} x {H:g} mm specimen{seed_text}: aggregate {rank + 1} of "
            f"{len(aggs)} (sieve size {a.sieve_size:.3g} mm) found no free position in max_placement_attempts = "
            f"{p.max_placement_attempts} random tries. The {len(aggs)} drawn cover {100 * drawn:.1f} % of the specimen "
            f"(aggregate_area_fraction = {p.aggregate_area_fraction:g}; the draw stops at the aggregate that brings "
            f"the total closest to it, so a few large aggregates can overshoot it); the {len(placed)} placed cover "
            f"{100 * done:.1f} %. A small specimen holds a few aggregates as large as itself, and whether they fit depends "
            f"on the seed: with the default grading (sieve sizes up to 10 mm) every seed tried places them from "
            f"{MIN_RELIABLE_SIZE_MM:g} x {MIN_RELIABLE_SIZE_MM:g} mm on, while 1 seed in 4 fails at 15 mm "
            f"(docs/guide.md, 'Specimen size'). Use another seed, a larger specimen, or a lower "
            f"aggregate_area_fraction, min_gap_mm or wall_gap_mm.")
