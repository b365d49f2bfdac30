# SPDX-License-Identifier: GPL-2.0-or-later
"""Parameters of the mesostructure generator and their validation.

Lengths given to the generator are in millimetres (names end in ``_mm``) for
convenience; the generated :class:`~swelldem.meso.assembly.Assembly` stores SI
metres. Every check runs before any work starts and raises
:class:`MesoParameterError` naming the parameter, its value and the allowed range.
"""
import dataclasses
import math
from dataclasses import dataclass
from typing import Tuple

#: Default sieve fractions (mm) of the paper's concrete: coarse sand and fine gravel.
PAPER_FRACTIONS_MM = ((2.4, 4.75), (4.75, 10.0))

#: Area shares of the two fractions in the coarse-aggregate area, from a Fuller
#: (maximum density) grading with D_max = 10 mm: passing p(d) = sqrt(d / 10), so the
#: two fractions hold sqrt(0.475) - sqrt(0.24) = 0.199 and 1 - sqrt(0.475) = 0.311 of the
#: aggregate volume, i.e. shares 0.39 / 0.61 (rounded to 0.4 / 0.6).
FULLER_SHARES = (0.4, 0.6)

#: Default coarse-aggregate (d >= 2.4 mm) area fraction: an ordinary concrete with
#: about 70 % aggregate by volume and the Fuller grading above has
#: 0.70 x (1 - sqrt(2.4 / 10)) = 0.357 of its volume in particles larger than 2.4 mm;
#: by Delesse's principle a random plane section shows the same area fraction.
DEFAULT_AGGREGATE_AREA_FRACTION = 0.35

#: Largest aggregate area fraction accepted (random sequential placement of convex
#: polygons with a mortar gap jams well before 0.7).
MAX_AGGREGATE_AREA_FRACTION = 0.6

#: Upper bound on the number of discs, W H / (pi rmin^2), accepted.
MAX_DISCS = 5_000_000

#: Upper bound on the number of spheres, W H D / (4/3 pi rmin^3), accepted: the bound is about 3.3 times
#: the spheres a packing holds (0.60 / 0.18 of the box at Rmin/Rmax = 2/3), so 1e6 admits a 50 mm cube
#: (about 270,000 spheres, hours of packing on one core) and refuses a 100 mm one.
MAX_SPHERES = 1_000_000

DIMS = (2, 3)

#: Largest 2D vertex count accepted in 3D: 81 points a polyhedron, about 0.3 s to draw one (at the
#: default 6-10, 11-32 points, 0.03 s).
MAX_VERTICES_3D = 16

LABEL_RULES = ("centre", "inside")


class MesoParameterError(ValueError):
    """A generator parameter is out of its allowed range (raised before any work starts)."""

    def __init__(self, name, value, allowed):
        self.name = name
        self.value = value
        self.allowed = allowed
        # the one message form of every swelldem setting (swelldem.options)
        for lead in ("must be ", "allowed range "):
            if allowed.startswith(lead):
                allowed = allowed[len(lead):]
        super().__init__(f"swelldem: {name} = {value!r} is out of range; allowed: {allowed}")


@dataclass(frozen=True)
class MesoParameters:
    """Parameters of :func:`swelldem.meso.generate` (lengths in mm unless the name says otherwise).

    Attributes:
        dim: 2 (a section of discs, the paper's model) or 3 (a box of spheres and polyhedral aggregates).
        width_mm, height_mm: specimen size [mm]; the specimen is [0, W] x [0, H] (x [0, D] in 3D).
        depth_mm: third side D of a 3D specimen [mm] (dim 3 only; a 2D section has thickness_m instead).
        thickness_m: out-of-plane thickness b of a 2D section [m]; facet area = facet length x b
            (paper: 1 m); unused in 3D, where a facet's area is its own.
        rmax_mm: largest disc (sphere) radius [mm] (paper: 2.4 / 5 = 0.48 mm).
        rmin_ratio: Rmin / Rmax [-], in (0, 1] (paper: 2/3); radii are uniform in [Rmin, Rmax].
        sieve_fractions_mm: aggregate sieve fractions ((d_lo, d_hi), ...) [mm]; the sieve
            size of a polygon is its smallest width (caliper diameter).
        fraction_shares: share of each fraction in the aggregate area [-], summing to 1.
        aggregate_area_fraction: aggregate polygon area / specimen area [-], in [0, 0.6]; in 3D the
            aggregate volume fraction (the same number by Delesse's principle: a random section of a
            concrete shows its volume fraction as area fraction).
        min_gap_mm: smallest mortar gap between two aggregate polygons [mm].
        wall_gap_mm: smallest distance from a polygon to the specimen sides [mm].
        aspect_ratio_range: (lo, hi) of the aggregate aspect ratio, length / width [-], 1 <= lo <= hi <= 4.
        vertices_range: (lo, hi) number of vertices drawn for a polygon before its convex hull, 3..64
            (3..16 in 3D, where a polyhedron gets round(n^2 / pi) points: the same angular spacing).
        angularity: 0 (regular polygon, then stretched) .. 1 (vertex angles jittered by up to half
            their spacing and radii by up to +-35 %): how irregular and sharp the shapes are [-].
        contact_gap_ratio: two discs sharing a Laguerre facet are in contact when their gap
            d - ri - rj <= (contact_gap_ratio + 1e-9) x rmax [-], in [0, 1] (the 1e-9 keeps
            tangent discs whose computed gap is a rounding error above zero).
        label_rule: "centre" (a disc is aggregate when its centre is inside a polygon) or
            "inside" (when the whole disc is inside it).
        max_placement_attempts: random positions tried per aggregate before giving up [-].
    """

    width_mm: float = 100.0
    height_mm: float = 100.0
    depth_mm: float = 100.0
    dim: int = 2
    thickness_m: float = 1.0
    rmax_mm: float = 0.48
    rmin_ratio: float = 2.0 / 3.0
    sieve_fractions_mm: Tuple[Tuple[float, float], ...] = PAPER_FRACTIONS_MM
    fraction_shares: Tuple[float, ...] = FULLER_SHARES
    aggregate_area_fraction: float = DEFAULT_AGGREGATE_AREA_FRACTION
    min_gap_mm: float = 0.5
    wall_gap_mm: float = 0.5
    aspect_ratio_range: Tuple[float, float] = (1.0, 1.8)
    vertices_range: Tuple[int, int] = (6, 10)
    angularity: float = 0.5
    contact_gap_ratio: float = 0.05
    label_rule: str = "centre"
    max_placement_attempts: int = 5000

    # ------------------------------------------------------------------ derived
    @property
    def rmin_mm(self):
        """Smallest disc radius [mm]."""
        return self.rmax_mm * self.rmin_ratio

    def replace(self, **changes):
        """A copy with some fields changed (unknown names raise MesoParameterError)."""
        names = {f.name for f in dataclasses.fields(self)}
        for k in changes:
            if k not in names:
                raise MesoParameterError(k, changes[k], f"unknown parameter; known: {sorted(names)}")
        return dataclasses.replace(self, **changes)

    def to_dict(self):
        """Plain-JSON dictionary of the parameters (lengths in mm as named)."""
        d = dataclasses.asdict(self)
        d["sieve_fractions_mm"] = [list(map(float, f)) for f in self.sieve_fractions_mm]
        d["fraction_shares"] = [float(s) for s in self.fraction_shares]
        d["aspect_ratio_range"] = [float(v) for v in self.aspect_ratio_range]
        d["vertices_range"] = [int(v) for v in self.vertices_range]
        return d

    @classmethod
    def from_dict(cls, d):
        """Inverse of :meth:`to_dict` (unknown keys raise MesoParameterError)."""
        d = dict(d)
        if "sieve_fractions_mm" in d:
            d["sieve_fractions_mm"] = tuple(tuple(float(v) for v in f) for f in d["sieve_fractions_mm"])
        for k in ("fraction_shares", "aspect_ratio_range", "vertices_range"):
            if k in d:
                d[k] = tuple(d[k])
        return cls().replace(**d)

    # --------------------------------------------------------------- validation
    def validate(self):
        """Raise MesoParameterError for the first parameter out of range; return self."""

        def num(name, lo=None, hi=None, lo_open=False, hi_open=False, what=None):
            v = getattr(self, name)
            try:
                fv = float(v)
            except (TypeError, ValueError):
                raise MesoParameterError(name, v, "must be a number") from None
            bad = not math.isfinite(fv)
            if lo is not None:
                bad |= fv <= lo if lo_open else fv < lo
            if hi is not None:
                bad |= fv >= hi if hi_open else fv > hi
            if bad:
                lb = "(" if lo_open else "["
                rb = ")" if hi_open else "]"
                rng = f"{lb}{'-inf' if lo is None else lo}, {'inf' if hi is None else hi}{rb}"
                raise MesoParameterError(name, v, what or f"allowed range {rng}")
            return fv

        dim = self.dim
        if isinstance(dim, bool) or dim not in DIMS:
            raise MesoParameterError("dim", dim, f"must be one of {DIMS}")
        W = num("width_mm", 0, lo_open=True, what="must be a finite length > 0 mm")
        H = num("height_mm", 0, lo_open=True, what="must be a finite length > 0 mm")
        sides = (W, H)
        if dim == 3:
            sides = (W, H, num("depth_mm", 0, lo_open=True, what="must be a finite length > 0 mm"))
        box = " x ".join(f"{v:g}" for v in sides)
        num("thickness_m", 0, lo_open=True, what="must be a finite thickness > 0 m")
        rmax = num("rmax_mm", 0, lo_open=True, what="must be a finite radius > 0 mm")
        ratio = self.rmin_ratio
        try:
            ratio_f = float(ratio)
        except (TypeError, ValueError):
            raise MesoParameterError("rmin_ratio", ratio, "must be a number") from None
        if not (math.isfinite(ratio_f) and ratio_f > 0):
            raise MesoParameterError("rmin_ratio", ratio, "Rmin / Rmax must be in (0, 1]")
        if ratio_f > 1:
            raise MesoParameterError(
                "rmin_ratio", ratio,
                f"Rmin = {ratio_f * rmax:g} mm > Rmax = {rmax:g} mm; Rmin / Rmax must be in (0, 1]")
        particle = "disc" if dim == 2 else "sphere"
        if 2 * rmax > min(sides):
            raise MesoParameterError("rmax_mm", self.rmax_mm,
                                     f"a {particle} of diameter {2 * rmax:g} mm does not fit the "
                                     f"{box} mm specimen; allowed range (0, {min(sides) / 2:g}]")
        if dim == 2:
            n_bound, n_max = W * H / (math.pi * (ratio_f * rmax) ** 2), MAX_DISCS
        else:
            n_bound, n_max = math.prod(sides) / (4.0 / 3.0 * math.pi * (ratio_f * rmax) ** 3), MAX_SPHERES
        if n_bound > n_max:
            raise MesoParameterError("rmax_mm", self.rmax_mm,
                                     f"up to {n_bound:.3g} {particle}s for a {box} mm specimen; "
                                     f"at most {n_max} allowed (raise rmax_mm or shrink the specimen)")
        phi = num("aggregate_area_fraction", 0, MAX_AGGREGATE_AREA_FRACTION)
        gap = num("min_gap_mm", 0, what="must be a finite length >= 0 mm")
        wgap = num("wall_gap_mm", 0, what="must be a finite length >= 0 mm")
        num("angularity", 0, 1)
        num("contact_gap_ratio", 0, 1)
        if self.label_rule not in LABEL_RULES:
            raise MesoParameterError("label_rule", self.label_rule, f"must be one of {LABEL_RULES}")
        mpa = self.max_placement_attempts
        if not isinstance(mpa, int) or isinstance(mpa, bool) or mpa < 1:
            raise MesoParameterError("max_placement_attempts", mpa, "must be an integer >= 1")

        ar = self.aspect_ratio_range
        if (not _is_pair(ar) or not all(math.isfinite(float(v)) for v in ar)
                or not (1.0 <= float(ar[0]) <= float(ar[1]) <= 4.0)):
            raise MesoParameterError("aspect_ratio_range", ar, "must be (lo, hi) with 1 <= lo <= hi <= 4")
        vr = self.vertices_range
        if (not _is_pair(vr) or not all(isinstance(v, int) and not isinstance(v, bool) for v in vr)
                or not (3 <= vr[0] <= vr[1] <= 64)):
            raise MesoParameterError("vertices_range", vr, "must be integers (lo, hi) with 3 <= lo <= hi <= 64")
        if dim == 3 and vr[1] > MAX_VERTICES_3D:
            raise MesoParameterError("vertices_range", vr,
                                     f"must be integers (lo, hi) with 3 <= lo <= hi <= {MAX_VERTICES_3D} in 3D "
                                     f"(a polyhedron gets round(hi^2 / pi) points, {round(MAX_VERTICES_3D ** 2 / math.pi)} "
                                     "at most; its smallest-width search grows as the square of its edges)")

        fr = self.sieve_fractions_mm
        sh = self.fraction_shares
        try:
            fr_list = [tuple(float(v) for v in f) for f in fr]
        except (TypeError, ValueError):
            raise MesoParameterError("sieve_fractions_mm", fr, "must be a sequence of (d_lo, d_hi) in mm") from None
        if len(fr_list) == 0 and phi > 0:
            raise MesoParameterError("sieve_fractions_mm", fr, "at least one fraction is needed when "
                                     "aggregate_area_fraction > 0")
        for k, f in enumerate(fr_list):
            if len(f) != 2 or not all(math.isfinite(v) for v in f) or not (0 < f[0] < f[1]):
                raise MesoParameterError("sieve_fractions_mm", fr,
                                         f"fraction {k} = {f} must be (d_lo, d_hi) with 0 < d_lo < d_hi mm")
        try:
            sh_list = [float(s) for s in sh]
        except (TypeError, ValueError):
            raise MesoParameterError("fraction_shares", sh, "must be a sequence of numbers") from None
        if len(sh_list) != len(fr_list):
            raise MesoParameterError("fraction_shares", sh,
                                     f"needs one share per sieve fraction ({len(fr_list)} fractions)")
        for s in sh_list:
            if not (math.isfinite(s) and 0 <= s <= 1):
                raise MesoParameterError("fraction_shares", sh, "every share must be in [0, 1]")
        if fr_list and abs(sum(sh_list) - 1.0) > 1e-6:
            raise MesoParameterError("fraction_shares", sh,
                                     f"shares sum to {sum(sh_list):.6g}; they must sum to 1 (+-1e-6)")
        if phi > 0:
            room = min(sides) - 2 * wgap
            for k, (f, s) in enumerate(zip(fr_list, sh_list)):
                if s > 0 and f[1] > room:
                    raise MesoParameterError(
                        "sieve_fractions_mm", fr,
                        f"fraction {k} = {f[0]:g}-{f[1]:g} mm does not fit the {box} mm specimen "
                        f"with wall_gap_mm = {wgap:g}: d_hi must be <= {room:g} mm (or give it share 0, "
                        f"or set aggregate_area_fraction = 0)")
            if gap > min(sides):
                raise MesoParameterError("min_gap_mm", self.min_gap_mm, f"allowed range [0, {min(sides):g}]")
        return self


def _is_pair(v):
    try:
        return len(v) == 2
    except TypeError:
        return False
