# SPDX-License-Identifier: GPL-2.0-or-later
"""Moisture transport on the particle network: a relative humidity h per particle, nonlinear
diffusion dh/dt = div(D(h) grad h) solved by finite volumes on the Laguerre cells of an Assembly.

Plain numpy/scipy (no YADE), in 2D (discs, out-of-plane thickness b) and 3D (spheres). What and why:

- Unknown and capacity. Each particle's Laguerre cell is a control volume of volume
  V_i = cell area x b (2D) or the cell volume (3D), holding one value h_i [-]. The equation is the
  issue's dh/dt = div(D grad h): the moisture capacity dw/dh is taken constant and the same for
  every particle, so the stored "water" reported here is the volume integral of h, sum V_i h_i
  [m^3]; times a capacity dw/dh [kg/m^3] it is a mass of water.
- Fluxes. Every pair of Laguerre neighbours (Assembly.neighbours, all of them, not only the
  bonded contacts) shares a facet of area A_ij (2D: facet length x b) that is perpendicular to the
  line of centres (a property of power diagrams), so the two-point flux
  q_ij = D_ij A_ij / d_ij (h_j - h_i), d_ij the centre distance, is the consistent finite-volume
  flux: it is exact for any linear field, because every cell closes (the sum of its facet areas
  times their outward normals, boundary facets included, is zero; checked when a network is
  built). The network's effective diffusivity therefore equals the conduits' D: the micro-macro
  factor that effective_diffusivity() measures is 1 to round-off on any packing (docs/moisture.md).
- Diffusivity. Bazant and Najjar's D(h) = D1 [alpha0 + (1 - alpha0) / (1 + ((1 - h)/(1 - hc))^n)]
  (Materiaux et Constructions 5(1), 1972, 3-20) with one parameter set per contact kind of the
  pair (MORTAR, ITZ, AGG, by swelldem.meso.contact_kinds, the assembly's own rule). A conduit's D
  is the mean of D(h) over [h_i, h_j], (Phi(h_j) - Phi(h_i)) / (h_j - h_i) with the Kirchhoff
  potential Phi(h) = integral of D from 0 to h: the exact conductance of a conduit in steady state,
  whatever D(h) does between its two ends ("kirchhoff", the default). The two simpler rules, D at
  the mean of the two h ("midpoint") and the harmonic mean of D(h_i) and D(h_j) ("harmonic"), are
  kept as conduit_mean options: all three agree to second order where h varies little over a
  conduit, but Bazant-Najjar's D drops 20-fold between h = 0.9 and 0.6 (n = 15 makes the drop a
  few hundredths of h wide), so a conduit across a drying front is underestimated 3- to 6-fold by
  the simple rules: against a fine 1D reference the midpoint rule is 19 % of the drop off at
  D1 t / L^2 = 0.02, the harmonic mean 11 %, the Kirchhoff mean 1.8 % (docs/moisture.md). Phi is
  tabulated once per kind on 8192 intervals of h (4-point Gauss-Legendre each) and interpolated by
  cubic Hermite with Phi' = D (relative error < 1e-11).
- Boundary. Each specimen face (x-, x+, y-, y+, and z-, z+ in 3D) is sealed (no flux) or exposed
  to an ambient h_a(t), a history (days, h) interpolated linearly (the end values hold outside
  it). A cell touching an exposed face exchanges through the same two-point form: conductance
  D A_b / delta_i, A_b the cell's area on the face and delta_i the distance from the centre to the
  face, D the conduit mean over [h_i, h_a] with the particle's own material (MORTAR parameters for a
  mortar particle, AGG for an aggregate one). A_b comes from the power diagram itself: in 2D the
  owners of the face are the lower envelope of the particles' power functions along it (a 1D power
  diagram), in 3D the library's clipped cells (swelldem.meso._geom.laguerre_box, box_area).
- Time. Backward Euler on the caller's times (days; the runs' log-spaced physical steps); D is in
  m^2/s and the steps are converted with 86400 s/day. Backward Euler keeps the discrete maximum
  principle (the step's matrix is an M-matrix), so h stays between its initial and ambient bounds.
- Nonlinearity: Newton's method. With Kirchhoff conduits a pair's flux is (A/d)(Phi(h_j) -
  Phi(h_i)), so the step's residual V (h - h_old)/dt - net inflow(h) has an exact, cheap Jacobian:
  V/dt plus the geometric Laplacian (A/d) with column j scaled by D(h_j). It is not symmetric but
  it is an M-matrix (positive diagonal, non-positive off-diagonal, diagonally dominant by columns),
  factorised without pivoting. Iterations stop when the largest correction of h is <= ``tol``
  (default 1e-8), at most ``max_iterations`` (default 50), else RuntimeError naming the step.
  Newton rather than Picard (conductances from the last iterate, a symmetric positive definite
  system each time), which the "midpoint" and "harmonic" means use, their conductances having no
  such simple derivative: on a slab drying to h = 0.5, Picard takes 8-16 iterations a step on
  average and up to 47, and fails to converge in 50 at some of 2, 5 and 10 steps a decade (the
  paper's range); Newton takes at most 7 from 2 to 80 steps a decade (docs/moisture.md). A constant D (alpha0 = 1 for every kind) is linear: one solve a step. Each
  solve is a sparse direct factor (scipy.sparse.linalg.splu, minimum-degree ordering of A + A^T)
  with one step of iterative refinement; the unknown is the increment h - h_old.
- Mass balance. Per step the water that leaves through the exposed faces, dt x the boundary fluxes
  of the last linear solve (the new h's own fluxes to within the tolerance squared), equals the
  decrease of the stored water sum V_i h_i to round-off: internal fluxes cancel pair by pair, and
  the step's linear equation holds to the solver's precision. Both are recorded per step
  (MoistureHistory), with the residual (~1e-15 of the step's change).

Parameters (D1 in m^2/s; alpha0, hc, n dimensionless), DEFAULT_KINDS:

| kind   | D1 [m^2/s]          | alpha0 | hc   | n  | source |
|--------|---------------------|--------|------|----|--------|
| MORTAR | 3.1e-10             | 0.05   | 0.80 | 15 | fib Model Code 2010 (as Model Code 1990): alpha0 = 0.05, hc = 0.80, n = 15, D1 = D1,0 / (fck - 8) with D1,0 = 1e-8 m^2/s, fck [MPa]: 3.1e-10 for fck = 40 MPa; the same D1 = 3.10e-10 m^2/s as Bazant, Chern and Thonguthai (Nucl. Eng. Des. 68, 1982), whose alpha at 20 C is 1/(1 + 19 x 75/70) = 0.047 |
| ITZ    | 2.5 x MORTAR = 7.75e-10 | 0.05 | 0.80 | 15 | the ITZ's water vapour diffusivity is about 60 x the bulk paste's (J. Mater. Civ. Eng. 28(10), 2016, doi:10.1061/(ASCE)MT.1943-5533.0001637) over an ITZ 10-30 um wide (Garboczi and Bentz, NIST); a conduit is 2 R_mean = 0.79 mm long, so a 20 um ITZ in parallel with mortar gives 1 + 59 x 0.020/0.79 = 2.5 |
| AGG    | 1e-3 x MORTAR = 3.1e-13 | 0.05 | 0.80 | 15 | aggregates are taken as non-conducting in mesoscale diffusion models (Li, Xia and Lin, Constr. Build. Mater. 26, 2012, 295-301; Dehghanpoor Abyaneh, Wong and Buenfeld, Comput. Mater. Sci. 78, 2013, 63-73); a thousandth of the mortar's keeps D1 positive |

Not part of this module yet: the coupling of h to swelling (the swelling increment's factor f(h))
and to drying shrinkage, scenario options and outputs.
"""
import functools
import math
from dataclasses import dataclass
from typing import Tuple

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .paper import AGG, KIND_NAMES, MORTAR

#: Seconds per day: the times are in days (DESIGN.md, physical time), the diffusivities in m^2/s.
SECONDS_PER_DAY = 86400.0

#: The specimen faces of each dimension, in the order of the boundary arrays' columns.
FACES = {2: ("x-", "x+", "y-", "y+"), 3: ("x-", "x+", "y-", "y+", "z-", "z+")}

#: Relative tolerance of the cells' closure (sum of facet area x outward normal, boundary facets
#: included, over the cell's facet area), checked when a network is built: measured ~1e-15 on
#: generated assemblies; a missing neighbour (e.g. particles removed by Assembly.without) is O(1).
CLOSURE_TOLERANCE = 1e-9


def _fail(name, value, allowed):
    return ValueError(f"swelldem.moisture: {name} = {value} is out of range; allowed: {allowed}")


def _is_number(x):
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool)


def _finite_number(x):
    return _is_number(x) and math.isfinite(float(x))


@dataclass(frozen=True)
class KindDiffusivity:
    """Bazant and Najjar's D(h) of one contact kind.

    d1_m2_s [m^2/s]: D at saturation (h = 1), > 0; alpha0 [-]: D(0) / D1 roughly (the floor of the
    drop), in (0, 1] (1: constant D = D1); hc [-]: the h of the drop's middle, in (0, 1); n [-]: the
    steepness of the drop, > 0.
    """

    d1_m2_s: float
    alpha0: float = 0.05
    hc: float = 0.80
    n: float = 15.0

    def validate(self, kind="kind"):
        """Raise ValueError naming the parameter (as ``kinds['<kind>'].<field>``) if out of range."""
        checks = (("d1_m2_s", lambda v: v > 0, "0 < d1_m2_s < inf [m^2/s]"),
                  ("alpha0", lambda v: 0 < v <= 1, "0 < alpha0 <= 1"),
                  ("hc", lambda v: 0 < v < 1, "0 < hc < 1"),
                  ("n", lambda v: v > 0, "0 < n < inf"))
        for name, ok, allowed in checks:
            v = getattr(self, name)
            if not (_finite_number(v) and ok(float(v))):
                raise _fail(f"kinds['{kind}'].{name}", v, allowed)
        return self

    def __call__(self, h):
        """D(h) [m^2/s] for h [-] (array or number); h above 1 (round-off) counts as 1."""
        u = np.maximum(1.0 - np.asarray(h, dtype=float), 0.0) / (1.0 - self.hc)
        return self.d1_m2_s * (self.alpha0 + (1.0 - self.alpha0) / (1.0 + u ** self.n))


#: Mortar's D1 [m^2/s]: fib Model Code 2010 for fck = 40 MPa, 1e-8 / (40 - 8); Bazant, Chern and
#: Thonguthai 1982 give 3.10e-10 (see the module's table).
MORTAR_D1_M2_S = 3.1e-10
#: ITZ conduits: D1 over the mortar's (a 20 um ITZ, 60 x faster, in parallel over a 0.79 mm conduit).
ITZ_D1_FACTOR = 2.5
#: Aggregate conduits: D1 over the mortar's (aggregates nearly non-conducting).
AGG_D1_FACTOR = 1e-3
#: The default parameters of each kind (module table).
DEFAULT_KINDS = {
    "MORTAR": KindDiffusivity(MORTAR_D1_M2_S),
    "ITZ": KindDiffusivity(ITZ_D1_FACTOR * MORTAR_D1_M2_S),
    "AGG": KindDiffusivity(AGG_D1_FACTOR * MORTAR_D1_M2_S),
}


def constant_kinds(d1_m2_s):
    """A kind table with the same constant D = d1_m2_s [m^2/s] for every kind (alpha0 = 1)."""
    return {name: KindDiffusivity(d1_m2_s, alpha0=1.0) for name in KIND_NAMES}


#: How a conduit's D is taken from the D(h) of its two ends (module docstring): "kirchhoff" the mean
#: of D over [h_i, h_j] (the default), "midpoint" D at the mean h, "harmonic" the harmonic mean of
#: the two ends' D.
CONDUIT_MEANS = ("kirchhoff", "midpoint", "harmonic")

# Intervals of the Kirchhoff potential's table over h in [0, 1] (width 1.2e-4, against a drop of
# D(h) a few hundredths wide for n = 15): the cubic Hermite interpolation is exact to ~1e-12.
_PHI_INTERVALS = 8192
# Below this |h_j - h_i| the difference of Phi loses digits; D at the midpoint is then exact to
# (1e-9)^2 x D'' / 24, far below round-off.
_PHI_MIN_SPAN = 1e-9


@functools.lru_cache(maxsize=64)
def _phi_table(kind):
    """(Phi at the nodes [m^2/s], D at the nodes [m^2/s]) of a KindDiffusivity on [0, 1]."""
    g, w = np.polynomial.legendre.leggauss(4)
    nodes = np.linspace(0.0, 1.0, _PHI_INTERVALS + 1)
    dx = 1.0 / _PHI_INTERVALS
    inner = nodes[:-1, None] + 0.5 * (g[None, :] + 1.0) * dx
    increments = (kind(inner) * w[None, :]).sum(axis=1) * 0.5 * dx
    return np.concatenate([[0.0], np.cumsum(increments)]), kind(nodes)


def kirchhoff_potential(kind, h):
    """Phi(h) = integral of D from 0 to h [m^2/s] of a KindDiffusivity, for h [-]; outside [0, 1]
    (round-off, or a Newton iterate) continued with the end slopes D(0) and D(1)."""
    phi, d = _phi_table(kind)
    h = np.asarray(h, dtype=float)
    s = np.clip(h, 0.0, 1.0) * _PHI_INTERVALS
    k = np.minimum(s.astype(np.int64), _PHI_INTERVALS - 1)
    t = s - k
    dx = 1.0 / _PHI_INTERVALS
    inside = ((2 * t ** 3 - 3 * t ** 2 + 1) * phi[k] + (t ** 3 - 2 * t ** 2 + t) * dx * d[k]
              + (-2 * t ** 3 + 3 * t ** 2) * phi[k + 1] + (t ** 3 - t ** 2) * dx * d[k + 1])
    return inside + np.minimum(h, 0.0) * d[0] + np.maximum(h - 1.0, 0.0) * d[-1]


def conduit_diffusivity(kind, h_a, h_b, mean="kirchhoff"):
    """A conduit's D [m^2/s] between ends at h_a and h_b [-] (arrays), by one of CONDUIT_MEANS."""
    h_a = np.asarray(h_a, dtype=float)
    h_b = np.asarray(h_b, dtype=float)
    if mean == "midpoint":
        return kind(0.5 * (h_a + h_b))
    if mean == "harmonic":
        da, db = kind(h_a), kind(h_b)
        return 2.0 * da * db / (da + db)
    span = h_b - h_a
    short = np.abs(span) < _PHI_MIN_SPAN
    out = np.empty(np.broadcast(h_a, h_b).shape)
    out[short] = kind(0.5 * (h_a + h_b)[short])
    far = ~short
    out[far] = (kirchhoff_potential(kind, h_b[far]) - kirchhoff_potential(kind, h_a[far])) / span[far]
    return out


def _check_kinds(kinds):
    if kinds is None:
        return dict(DEFAULT_KINDS)
    if not isinstance(kinds, dict) or set(kinds) != set(KIND_NAMES):
        got = sorted(kinds) if isinstance(kinds, dict) else kinds
        raise _fail("kinds", got, f"a dict with exactly the keys {', '.join(KIND_NAMES)}, values KindDiffusivity")
    for name in KIND_NAMES:
        if not isinstance(kinds[name], KindDiffusivity):
            raise _fail(f"kinds['{name}']", kinds[name], "a KindDiffusivity")
        kinds[name].validate(name)
    return dict(kinds)


def _lower_envelope(a, b, lo, hi):
    """Where each line of min_i (a_i s + b_i) is lowest on [lo, hi]: a list of (i, s0, s1).

    The owner at lo is the lowest line (ties: the one that descends fastest); the next owner is,
    among the lines descending faster than the current one, the one that crosses it first
    (ties: the fastest). Each change lowers the owner's slope, so there are at most len(a) pieces.
    """
    v = a * lo + b
    tied = np.flatnonzero(v == v.min())
    owner = int(tied[np.argmin(a[tied])])
    s, out = lo, []
    eps = 1e-12 * (hi - lo)
    while True:
        steeper = np.flatnonzero(a < a[owner])
        nxt = hi
        if steeper.size:
            cross = (b[steeper] - b[owner]) / (a[owner] - a[steeper])
            nxt = max(float(cross.min()), s)
        if nxt >= hi:
            out.append((owner, s, hi))
            return out
        near = steeper[cross <= nxt + eps]
        new = int(near[np.argmin(a[near])])
        out.append((owner, s, nxt))
        owner, s = new, nxt


def boundary_facets(assembly):
    """Each particle's Laguerre-cell facet on each specimen face: (measure, distance).

    measure (n, n_faces): 2D the boundary length [m] (multiply by thickness_m for an area), 3D the
    area [m^2]; distance (n, n_faces) [m]: from the particle's centre to the face. Columns in the
    order FACES[dim]. A face's measures sum to its length (2D) or area (3D).

    2D: the cells are the power cells of the discs (weights r^2) clipped to the specimen, so along
    a face the owner of a point is the disc of least power |p - c_i|^2 - r_i^2; on the face line
    that is a family of straight lines in the face coordinate (the common quadratic term drops),
    whose lower envelope gives each disc's boundary segment. 3D: the compiled library's clipped
    cells (laguerre_box's box_area), recomputed from the centres and radii; ValueError if their
    volumes do not match the assembly's.
    """
    n = assembly.n_particles
    if assembly.dim == 3:
        from .meso import _geom
        mm = 1e-3
        lag = _geom.laguerre_box(assembly.x / mm, assembly.y / mm, assembly.z / mm, assembly.r / mm,
                                 assembly.width_m / mm, assembly.height_m / mm, assembly.depth_m / mm, polygons=False)
        vol = lag["cell_volume"] * mm ** 3
        rel = float(np.max(np.abs(vol - assembly.cell_volume_m3)) / np.mean(assembly.cell_volume_m3)) if n else 0.0
        if rel > 1e-9:
            raise ValueError("swelldem.moisture: assembly = the 3D cells recomputed from the spheres differ from its "
                             f"cell_volume_m3 (by {rel:.1e} of the mean cell) is out of range; allowed: an assembly "
                             "whose cells tile its box, as swelldem.meso.generate makes it")
        measure = lag["box_area"] * mm ** 2
        pos = np.column_stack([assembly.x, assembly.y, assembly.z])
        size = np.array([assembly.width_m, assembly.height_m, assembly.depth_m])
    else:
        pos = np.column_stack([assembly.x, assembly.y])
        size = np.array([assembly.width_m, assembly.height_m])
        measure = np.zeros((n, 4))
        for axis in range(2):
            along = 1 - axis
            for side in range(2):
                c = side * size[axis]
                a = -2.0 * pos[:, along]
                b = (c - pos[:, axis]) ** 2 + pos[:, along] ** 2 - assembly.r ** 2
                for i, s0, s1 in _lower_envelope(a, b, 0.0, float(size[along])):
                    measure[i, 2 * axis + side] += s1 - s0
    distance = np.empty((n, 2 * assembly.dim))
    for axis in range(assembly.dim):
        distance[:, 2 * axis] = pos[:, axis]
        distance[:, 2 * axis + 1] = size[axis] - pos[:, axis]
    return measure, distance


@dataclass
class MoistureHistory:
    """The result of MoistureNetwork.run.

    times_days (m,) [day]; h (m, n) [-]: every particle's h at every time (row 0: the initial h);
    faces: the face names of the columns below; exposed: which faces were exposed;
    ambient (m, n_faces) [-]: each exposed face's ambient h at each time (NaN for sealed faces);
    stored_m3 (m,) [m^3]: the stored water sum V_i h_i (volume integral of h);
    per step k (from times_days[k] to times_days[k + 1], m - 1 of them):
    stored_loss_m3 (m - 1,) [m^3]: decrease of the stored water, sum V_i (h_old - h_new);
    gross_change_m3 (m - 1,) [m^3]: sum V_i |h_new - h_old|, the water moved in the step (equal to
    |stored_loss_m3| where every particle dries, or every one wets; > 0 even when all faces are sealed);
    outflow_m3 (m - 1, n_faces) [m^3]: water that left through each face (negative: entered);
    balance_residual_m3 (m - 1,) [m^3]: stored_loss - total outflow (round-off);
    iterations (m - 1,): Newton (Picard for the midpoint and harmonic means) iterations, i.e. linear
    solves, of each step.
    """

    times_days: np.ndarray
    h: np.ndarray
    faces: Tuple[str, ...]
    exposed: Tuple[bool, ...]
    ambient: np.ndarray
    stored_m3: np.ndarray
    stored_loss_m3: np.ndarray
    gross_change_m3: np.ndarray
    outflow_m3: np.ndarray
    balance_residual_m3: np.ndarray
    iterations: np.ndarray

    @property
    def total_outflow_m3(self):
        """(m - 1,) [m^3]: the water that left through all faces in each step."""
        return self.outflow_m3.sum(axis=1)

    def relative_balance_residual(self):
        """(m - 1,) [-]: |balance residual| / the step's gross change of stored water (0 where nothing
        changed): the balance's round-off, even in a step whose net loss is near zero."""
        gross = self.gross_change_m3
        return np.divide(np.abs(self.balance_residual_m3), gross, out=np.zeros_like(gross), where=gross > 0)


class MoistureNetwork:
    """The finite-volume network of an Assembly for moisture transport (module docstring).

    Built once per assembly: per neighbour pair its area A [m^2], centre distance d [m] and kind;
    per particle its capacity V [m^3] (cell area x thickness in 2D, cell volume in 3D) and its
    boundary facets on each face (area [m^2], centre-to-face distance [m]). kinds: {kind name:
    KindDiffusivity} for every name of swelldem.paper.KIND_NAMES (default DEFAULT_KINDS);
    conduit_mean: one of CONDUIT_MEANS (default "kirchhoff", the exact steady conduit).

    Raises ValueError (before any work on the fields) for a kind table out of range, or an
    assembly whose cells do not close (a missing neighbour facet, e.g. particles removed).
    """

    def __init__(self, assembly, kinds=None, conduit_mean="kirchhoff"):
        if assembly.dim not in FACES:
            raise _fail("assembly.dim", assembly.dim, "2 or 3")
        self.kinds = _check_kinds(kinds)
        if conduit_mean not in CONDUIT_MEANS:
            raise _fail("conduit_mean", repr(conduit_mean), ", ".join(CONDUIT_MEANS))
        self.conduit_mean = conduit_mean
        self.dim = int(assembly.dim)
        self.faces = FACES[self.dim]
        self.n = assembly.n_particles
        pairs = np.asarray(assembly.neighbours, dtype=np.int64).reshape(-1, 2)
        self.pairs = pairs
        pos = np.column_stack([assembly.x, assembly.y] + ([assembly.z] if self.dim == 3 else []))
        self.position_m = pos
        i, j = pairs[:, 0], pairs[:, 1]
        delta = pos[j] - pos[i]
        self.pair_distance_m = np.sqrt(np.sum(delta ** 2, axis=1))
        if self.dim == 2:
            b = float(assembly.thickness_m)
            self.pair_area_m2 = np.asarray(assembly.neighbour_facet_length_m, dtype=float) * b
            self.capacity_m3 = np.asarray(assembly.cell_area_m2, dtype=float) * b
            measure, self.boundary_distance_m = boundary_facets(assembly)
            self.boundary_area_m2 = measure * b
            self.specimen_size_m = (assembly.width_m, assembly.height_m)
            self.thickness_m = b
        else:
            self.pair_area_m2 = np.asarray(assembly.neighbour_facet_area_m2, dtype=float)
            self.capacity_m3 = np.asarray(assembly.cell_volume_m3, dtype=float)
            self.boundary_area_m2, self.boundary_distance_m = boundary_facets(assembly)
            self.specimen_size_m = (assembly.width_m, assembly.height_m, assembly.depth_m)
            self.thickness_m = None
        if self.n and not np.all(self.capacity_m3 > 0):
            k = int(np.flatnonzero(~(self.capacity_m3 > 0))[0])
            raise _fail(f"assembly cell of particle {k}", float(self.capacity_m3[k]), "a cell of positive size")
        from .meso.generator import contact_kinds  # the assembly's one rule for a pair's kind
        self.pair_kind = np.asarray(contact_kinds(i, j, assembly.aggregate_id), dtype=np.int8)
        # a boundary half-conduit lies in the particle's own material
        self.particle_kind = np.where(np.asarray(assembly.aggregate_id) >= 0, AGG, MORTAR).astype(np.int8)
        self.linear = all(self.kinds[k].alpha0 == 1.0 for k in KIND_NAMES)
        self._check_closure(delta)
        # the matrix pattern: the diagonal, then (i, j) and (j, i) for every pair
        idx = np.arange(self.n)
        self._rows = np.concatenate([idx, i, j])
        self._cols = np.concatenate([idx, j, i])
        self._geometry = self.pair_area_m2 / self.pair_distance_m        # A / d [m]
        self._boundary_geometry = np.divide(self.boundary_area_m2, self.boundary_distance_m,
                                            out=np.zeros_like(self.boundary_area_m2),
                                            where=self.boundary_area_m2 > 0)  # A_b / delta [m]

    # ---------------------------------------------------------------- geometry
    def _check_closure(self, delta):
        """Every cell must close: sum over its facets of area x outward unit normal = 0 (the
        boundary facets' normals are the faces'); this is what makes the two-point flux exact for
        linear fields, and it fails where a neighbour is missing."""
        i, j = self.pairs[:, 0], self.pairs[:, 1]
        unit = delta / self.pair_distance_m[:, None]
        vec = np.zeros((self.n, self.dim))
        for c in range(self.dim):
            np.add.at(vec[:, c], i, self.pair_area_m2 * unit[:, c])
            np.add.at(vec[:, c], j, -self.pair_area_m2 * unit[:, c])
            vec[:, c] += self.boundary_area_m2[:, 2 * c + 1] - self.boundary_area_m2[:, 2 * c]
        total = np.zeros(self.n)
        np.add.at(total, i, self.pair_area_m2)
        np.add.at(total, j, self.pair_area_m2)
        total += self.boundary_area_m2.sum(axis=1)
        rel = np.linalg.norm(vec, axis=1) / np.maximum(total, np.finfo(float).tiny)
        self.closure_error = float(rel.max()) if self.n else 0.0
        if self.closure_error > CLOSURE_TOLERANCE:
            k = int(np.argmax(rel))
            raise ValueError(f"swelldem.moisture: assembly cell of particle {k} = open (its facets sum to "
                             f"{self.closure_error:.1e} of their area) is out of range; allowed: closed Laguerre cells "
                             f"(relative {CLOSURE_TOLERANCE:g}), as swelldem.meso.generate makes them; an assembly "
                             "with particles removed (Assembly.without) has holes the transport does not model")

    # -------------------------------------------------------------- diffusivity
    def _conduit_d(self, kind_ids, h_a, h_b):
        """D [m^2/s] of conduits between ends at h_a and h_b, each with the parameters of its kind id."""
        out = np.empty(np.shape(h_a))
        for k, name in enumerate(KIND_NAMES):
            sel = kind_ids == k
            if np.any(sel):
                out[sel] = conduit_diffusivity(self.kinds[name], h_a[sel], h_b[sel], self.conduit_mean)
        return out

    def _phi_and_d(self, kind_ids, h):
        """(Phi [m^2/s], D [m^2/s]) at h [-], each entry with the parameters of its kind id."""
        phi, d = np.empty(np.shape(h)), np.empty(np.shape(h))
        for k, name in enumerate(KIND_NAMES):
            sel = kind_ids == k
            if np.any(sel):
                phi[sel] = kirchhoff_potential(self.kinds[name], h[sel])
                d[sel] = self.kinds[name](h[sel])
        return phi, d

    def pair_conductance(self, h):
        """(p,) [m^3/s]: conduit D over [h_i, h_j] x A / d of every neighbour pair, for particle h (n,)."""
        return self._conduit_d(self.pair_kind, h[self.pairs[:, 0]], h[self.pairs[:, 1]]) * self._geometry

    def boundary_conductance(self, h, ambient):
        """(n, n_faces) [m^3/s]: conduit D over [h_i, ambient] x A_b / delta of every cell on each face
        with an ambient value (ambient (n_faces,), NaN = sealed: conductance 0)."""
        g = np.zeros_like(self._boundary_geometry)
        for f, ha in enumerate(ambient):
            if np.isnan(ha):
                continue
            rows = np.flatnonzero(self._boundary_geometry[:, f] > 0)
            g[rows, f] = self._conduit_d(self.particle_kind[rows], h[rows], np.full(rows.size, float(ha))) \
                * self._boundary_geometry[rows, f]
        return g

    # ----------------------------------------------------------------- solving
    def _matrix(self, diagonal, k):
        """The symmetric matrix diag(diagonal + sum of k over each row's pairs) - k off the diagonal."""
        d = np.array(diagonal, dtype=float, copy=True)
        np.add.at(d, self.pairs[:, 0], k)
        np.add.at(d, self.pairs[:, 1], k)
        data = np.concatenate([d, -k, -k])
        return sp.csc_matrix((data, (self._rows, self._cols)), shape=(self.n, self.n))

    def _picard_system(self, u, h_old, c_dt, ambient):
        """One Picard iteration of a step: conductances from the iterate h_old + u, unknown the new
        increment u = h - h_old. Returns (matrix, right-hand side, boundary terms): the symmetric
        matrix V/dt + L + G and the net inflow of h_old, each pair's flux computed once and given to
        both cells; boundary terms [(face, rows, outflow at h_old [m^3/s], d outflow / d unknown)]."""
        h_it = h_old + u
        k = self.pair_conductance(h_it)
        g = self.boundary_conductance(h_it, ambient)
        i, j = self.pairs[:, 0], self.pairs[:, 1]
        q = k * (h_old[j] - h_old[i])
        rhs = np.zeros(self.n)
        np.add.at(rhs, i, q)
        np.add.at(rhs, j, -q)
        terms = []
        for f, ha in enumerate(ambient):
            if not np.isnan(ha):
                rows = np.flatnonzero(g[:, f] > 0)
                out = g[rows, f] * (h_old[rows] - ha)
                rhs[rows] -= out
                terms.append((f, rows, out, g[rows, f]))
        return self._matrix(c_dt + g.sum(axis=1), k), rhs, terms

    def _newton_system(self, u, h_old, c_dt, ambient):
        """One Newton iteration of a step with Kirchhoff conduits, whose flux is (A/d) (Phi(h_j) -
        Phi(h_i)): the residual V u / dt - net inflow(h_old + u) and its exact Jacobian V/dt + the
        geometric Laplacian with column j scaled by D(h_j) (an M-matrix, not symmetric); the unknown
        is the correction of u. Returns (Jacobian, -residual, boundary terms) as _picard_system."""
        h_it = h_old + u
        i, j = self.pairs[:, 0], self.pairs[:, 1]
        phi_i, d_i = self._phi_and_d(self.pair_kind, h_it[i])
        phi_j, d_j = self._phi_and_d(self.pair_kind, h_it[j])
        q = self._geometry * (phi_j - phi_i)
        rhs = -c_dt * u
        np.add.at(rhs, i, q)
        np.add.at(rhs, j, -q)
        diag = np.array(c_dt, dtype=float, copy=True)
        np.add.at(diag, i, self._geometry * d_i)
        np.add.at(diag, j, self._geometry * d_j)
        terms = []
        for f, ha in enumerate(ambient):
            if np.isnan(ha):
                continue
            rows = np.flatnonzero(self._boundary_geometry[:, f] > 0)
            kinds = self.particle_kind[rows]
            phi_b, d_b = self._phi_and_d(kinds, h_it[rows])
            phi_a, _ = self._phi_and_d(kinds, np.full(rows.size, float(ha)))
            gb = self._boundary_geometry[rows, f]
            out = gb * (phi_b - phi_a)
            rhs[rows] -= out
            diag[rows] += gb * d_b
            terms.append((f, rows, out, gb * d_b))
        data = np.concatenate([diag, -self._geometry * d_j, -self._geometry * d_i])
        jac = sp.csc_matrix((data, (self._rows, self._cols)), shape=(self.n, self.n))
        return jac, rhs, terms

    @staticmethod
    def _solve(a, rhs):
        lu = spla.splu(a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        x = lu.solve(rhs)
        return x + lu.solve(rhs - a @ x)  # one step of iterative refinement: the balance to round-off

    def _check_faces(self, faces):
        """{face: None | h | (days, h)} -> list of per-face ambient callables (None = sealed)."""
        if faces is None:
            faces = {}
        if not isinstance(faces, dict):
            raise _fail("faces", faces, "a dict {face: None (sealed), an ambient h, or a (days, h) history}")
        out = [None] * len(self.faces)
        for name, spec in faces.items():
            if name not in self.faces:
                raise _fail("face", repr(name), ", ".join(self.faces))
            label = f"faces['{name}']"
            if spec is None:
                continue
            if _is_number(spec):
                if not 0 < float(spec) <= 1:
                    raise _fail(label, spec, "0 < h <= 1, None (sealed) or a (days, h) history")
                out[self.faces.index(name)] = (np.array([0.0]), np.array([float(spec)]))
                continue
            try:
                days, hs = spec
                days = np.asarray(days, dtype=float).ravel()
                hs = np.asarray(hs, dtype=float).ravel()
            except (TypeError, ValueError):
                raise _fail(label, spec, "None (sealed), an ambient h in (0, 1], or a (days, h) history") from None
            if days.size == 0 or days.size != hs.size:
                raise _fail(f"{label} history", f"({days.size} days, {hs.size} h)", "the same number (>= 1) of days and h")
            if not np.all(np.isfinite(days)) or np.any(np.diff(days) <= 0):
                raise _fail(f"{label} days", days.tolist(), "finite and strictly increasing")
            bad = np.flatnonzero(~((hs > 0) & (hs <= 1)))
            if bad.size:
                raise _fail(f"{label} h[{bad[0]}]", float(hs[bad[0]]), "0 < h <= 1")
            out[self.faces.index(name)] = (days, hs)
        return out

    def _check_h0(self, h0):
        if _is_number(h0):
            h = np.full(self.n, float(h0))
        else:
            try:
                h = np.asarray(h0, dtype=float)
            except (TypeError, ValueError):
                raise _fail("h0", h0, "a number or an array of one h per particle, 0 < h0 <= 1") from None
            if h.shape != (self.n,):
                raise _fail("h0 shape", h.shape, f"a number or ({self.n},), one h per particle")
        bad = np.flatnonzero(~((h > 0) & (h <= 1)))
        if bad.size:
            name = "h0" if _is_number(h0) else f"h0[{bad[0]}]"
            raise _fail(name, float(h[bad[0]]), "0 < h0 <= 1")
        return h

    @staticmethod
    def _check_times(times_days):
        try:
            t = np.asarray(times_days, dtype=float).ravel()
        except (TypeError, ValueError):
            raise _fail("times_days", times_days, "a sequence of at least 2 finite, strictly increasing days") from None
        if t.size < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            shown = t.tolist() if t.size <= 8 else f"[{t[0]}, ... ({t.size} values)]"
            raise _fail("times_days", shown, "at least 2 finite, strictly increasing days")
        return t

    def run(self, times_days, h0, faces=None, tol=1e-8, max_iterations=50):
        """Backward Euler over times_days [day] from the initial h0 (a number or one h per particle,
        in (0, 1]), with faces {face: None (sealed), h (constant ambient) or (days, h) (an ambient
        history interpolated linearly, the end values holding outside it)}; faces not named are
        sealed. Each step iterates (Newton for Kirchhoff conduits, Picard for the other means) until
        the largest correction of h is <= tol [-], at most max_iterations times. Every input is
        checked before the first step (ValueError). Returns a MoistureHistory. Raises RuntimeError
        naming the step if the iteration does not converge.
        """
        t = self._check_times(times_days)
        h = self._check_h0(h0)
        histories = self._check_faces(faces)
        if not (_finite_number(tol) and tol > 0):
            raise _fail("tol", tol, "0 < tol < inf [-]")
        if isinstance(max_iterations, bool) or not isinstance(max_iterations, (int, np.integer)) or max_iterations < 1:
            raise _fail("max_iterations", max_iterations, "an integer >= 1")
        nf = len(self.faces)
        ambient = np.full((t.size, nf), np.nan)
        for f, hist in enumerate(histories):
            if hist is not None:
                ambient[:, f] = np.interp(t, hist[0], hist[1])
        m = t.size
        out_h = np.empty((m, self.n))
        out_h[0] = h
        loss = np.zeros(m - 1)
        gross = np.zeros(m - 1)
        outflow = np.zeros((m - 1, nf))
        iterations = np.zeros(m - 1, dtype=np.int64)
        for step in range(m - 1):
            dt = (t[step + 1] - t[step]) * SECONDS_PER_DAY
            ha = ambient[step + 1]
            c_dt = self.capacity_m3 / dt
            h_old = out_h[step]
            # the unknown is the increment u = h - h_old, so that the stored loss, sum V u, keeps
            # the solve's relative precision however small the step's change
            u = np.zeros(self.n)
            newton = self.conduit_mean == "kirchhoff"
            system = self._newton_system if newton else self._picard_system
            for it in range(1, max_iterations + 1):
                a, rhs, terms = system(u, h_old, c_dt, ha)
                x = self._solve(a, rhs)
                u_new = u + x if newton else x
                change = float(np.max(np.abs(u_new - u))) if self.n else 0.0
                u = u_new
                if self.linear or change <= tol:
                    break
            else:
                raise RuntimeError(f"swelldem.moisture: step {step} (from {t[step]:g} to {t[step + 1]:g} days) did not "
                                   f"converge in {max_iterations} {'Newton' if newton else 'Picard'} iterations (last "
                                   f"change of h {change:.3e} > tol {tol:g}); use shorter steps (more of them a decade) "
                                   "or a larger max_iterations")
            iterations[step] = it
            out_h[step + 1] = h_old + u
            loss[step] = -float(np.sum(self.capacity_m3 * u))
            gross[step] = float(np.sum(self.capacity_m3 * np.abs(u)))
            # the fluxes of the last linear solve: the step's equation holds for them to round-off
            for f, rows, out, slope in terms:
                outflow[step, f] = dt * float(np.sum(out + slope * x[rows]))
        stored = out_h @ self.capacity_m3
        return MoistureHistory(times_days=t, h=out_h, faces=self.faces,
                               exposed=tuple(hist is not None for hist in histories), ambient=ambient,
                               stored_m3=stored, stored_loss_m3=loss, gross_change_m3=gross, outflow_m3=outflow,
                               balance_residual_m3=loss - outflow.sum(axis=1), iterations=iterations)


def effective_diffusivity(network, axis="x", h_ref=1.0):
    """The network's effective diffusivity along an axis, from a steady-state flux test.

    Every conduit's D is frozen at its kind's D(h_ref); h is fixed to 1 on the face axis- and 0 on
    axis+, the other faces sealed; the steady flux Q [m^3/s] through the specimen gives
    D_eff = Q L / (S x 1), L the specimen's length along the axis, S its cross-section (2D: the
    other side x thickness). Returns (D_eff [m^2/s], D_eff / D_MORTAR(h_ref) [-]): the micro-macro
    factor of the network against the mortar conduits' D (1 to round-off for a mortar-only
    assembly: docs/moisture.md), or the homogenised concrete's D over the mortar's.
    """
    axes = "xyz"[: network.dim]
    if axis not in axes:
        raise _fail("axis", repr(axis), ", ".join(axes))
    if not (_is_number(h_ref) and 0 < float(h_ref) <= 1):
        raise _fail("h_ref", h_ref, "0 < h_ref <= 1")
    c = axes.index(axis)
    h_uniform = np.full(network.n, float(h_ref))
    k = network.pair_conductance(h_uniform)
    # conductances of the two faces at D(h_ref) (the other faces sealed); then h = 1 on axis-, 0 on axis+
    frozen = np.full(len(network.faces), np.nan)
    frozen[[2 * c, 2 * c + 1]] = float(h_ref)
    g = network.boundary_conductance(h_uniform, frozen)
    h = network._solve(network._matrix(g.sum(axis=1), k), g[:, 2 * c])
    flux_out = float(np.sum(g[:, 2 * c + 1] * h))
    size = network.specimen_size_m
    length = size[c]
    section = float(np.prod([s for q, s in enumerate(size) if q != c])) * (network.thickness_m if network.dim == 2 else 1.0)
    d_eff = flux_out * length / section
    return d_eff, d_eff / float(network.kinds["MORTAR"](h_ref))
