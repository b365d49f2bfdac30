# SPDX-License-Identifier: GPL-2.0-or-later
"""Straight reinforcing bars along x in a 2D specimen.

A bar is a row of touching steel discs (radius: the mesostructure's mean radius) on a line
y = y_b, from one side of the specimen to the other. It replaces the discs it overlaps
(Assembly.without: it also cuts through the aggregates it crosses, as the generator does not keep
them off the bars). Its steel (ConcreteMat.steel) makes three contact kinds:
- STEEL between consecutive bar discs: elastic, modulus E_s, with the bar's cross-section as
  contact area, A_s = t_b b (t_b the bar's thickness in the plane, b the model's thickness), so
  that kn L = E_s A_s is the bar's axial stiffness and Fn / A_s its stress. The steel does not
  yield: the bar stays elastic, and the first time its stress reaches f_y is reported
  (Bars.yield_day), not modelled.
- BOND between each remaining disc that faces the bar (within 1.5 Rmax of it and not hidden behind
  another disc, as for a platen) and the nearest bar disc, whatever the gap the carving left, as
  the concrete cast around a bar fills it: the mortar-steel interface, with the ITZ kind's creep
  (and temperature), stiffness and strength and no swelling of its own (the ITZ of the paper is the mortar's interface with an inclusion), breaking
  as the ITZ does.
- PLATEN where a bar's end touches a platen (swelldem.dem.platens).
The reinforcement ratio rho is the steel area over the specimen's cross-section: rho = n t_b / H
for n bars in a specimen of height H, so t_b = rho H / n. The bars are evenly spaced:
y_b = H (k + 1/2) / n.

The layout is a function of the options alone (size, ratio, bar count, the generator's disc
radii), not of the generated discs, so that a layout that does not fit is refused before the
mesostructure is made (SwellingTest.validate). It fits when every bar keeps a concrete cover of
at least one largest disc's diameter (2 Rmax) to the specimen's sides and the same clear spacing
to its neighbours: otherwise the carving leaves no concrete there for the bond to hold.
"""
from dataclasses import dataclass

import numpy as np

from .. import options, paper
from ..meso import MesoParameters
from . import scene as sc
from .platens import facing_discs

STEEL, BOND = "STEEL", "BOND"
#: Steel's modulus [Pa] and yield stress [Pa] (B500 reinforcing steel).
STEEL_YOUNG = 200e9
STEEL_YIELD = 500e6
#: Largest reinforcement ratio [-]: beyond it the bars' thickness approaches the discs' size.
MAX_RATIO = 0.1


@dataclass(frozen=True)
class RebarLayout:
    """Where the bars go, from the reinforcement ratio: n bars along x at y_m [m], each of
    thickness thickness_m [m] (rho H / n) in the plane, made of touching discs of radius radius_m
    [m] (about the mesostructure's mean radius), n_discs of them, that span the specimen's width."""
    ratio: float
    n_bars: int
    y_m: tuple
    thickness_m: float
    radius_m: float
    n_discs: int
    young: float = STEEL_YOUNG
    yield_stress: float = STEEL_YIELD


def bar_discs(width_m, r_mean_m=None):
    """(n_discs, radius [m]) of the touching discs of a bar that spans width_m [m]: as many as discs
    of the packing's mean radius r_mean_m would take (default: the generator's nominal mean,
    (Rmin + Rmax) / 2, its radii being uniform in [Rmin, Rmax]), resized to span the width exactly."""
    if r_mean_m is None:
        p = MesoParameters()
        r_mean_m = 0.5e-3 * (p.rmin_mm + p.rmax_mm)
    n_discs = max(1, int(round(width_m / (2 * r_mean_m))))
    return n_discs, width_m / (2 * n_discs)


def min_cover_m():
    """The least concrete cover of a bar [m], to a side and (as clear spacing) to the next bar: one
    diameter of the generator's largest disc, 2 Rmax."""
    return 2 * MesoParameters().rmax_mm * 1e-3


def layout(width_m, height_m, ratio, n_bars=1, young=STEEL_YOUNG, yield_stress=STEEL_YIELD, y_m=None):
    """The RebarLayout of `ratio` [-] (0 < ratio <= MAX_RATIO) in n_bars bars across a specimen of
    width_m x height_m [m], evenly spaced unless y_m [m] gives their heights; OptionError (naming
    the value and the allowed range) for a ratio, modulus, yield stress, bar count or bar position
    out of range or a layout that does not fit (a cover or clear spacing below min_cover_m()). Uses
    only these values, not the generated discs: run before any work."""
    options.number("rebar_ratio", ratio, lo=0, hi=MAX_RATIO, hi_incl=True)
    options.integer("rebar_bars", n_bars, lo=1)
    options.number("rebar_young", young, lo=0, unit="Pa")
    options.number("rebar_yield_stress", yield_stress, lo=0, unit="Pa")
    w, h = float(width_m), float(height_m)
    n_discs, r = bar_discs(w)
    cover = min_cover_m()
    if y_m is None:
        # evenly spaced: the cover to the sides, h / (2 n) - r, is half the clear spacing, h / n - 2 r
        n_max = int(np.floor(h / (2 * (r + cover)) * (1 + 1e-12)))
        if n_bars > n_max:
            options.bad("rebar_bars", n_bars,
                        (f"1 <= rebar_bars <= {n_max}" if n_max >= 1 else "none (rebar_ratio = 0)")
                        + f": bars of discs of diameter {2e3 * r:.3g} mm, evenly spaced across the {1e3 * h:g} mm height, each with "
                        f"a concrete cover of at least {1e3 * cover:.3g} mm (2 Rmax) to the sides and the next bar")
        ys = tuple(h * (k + 0.5) / n_bars for k in range(n_bars))
    else:
        ys = tuple(float(v) for v in y_m)
        if len(ys) != n_bars:
            options.bad("rebar_y_m", y_m, f"{n_bars} heights, one per bar")
    lo, hi = r + cover, h - r - cover
    for k, y in enumerate(ys):
        if not (np.isfinite(y) and lo <= y <= hi):
            options.bad(f"rebar_y_m[{k}]", y, f"a height inside the specimen with a concrete cover of {1e3 * cover:.3g} mm (2 Rmax): "
                                              f"{lo:.4g} <= y <= {hi:.4g} [m]")
    order = np.argsort(ys)
    for k0, k in zip(order[:-1], order[1:]):
        if ys[k] - ys[k0] < 2 * r + cover:
            options.bad(f"rebar_y_m[{k}]", ys[k], f"a height at least {2 * r + cover:.4g} m from every other bar's "
                                                  f"(a clear spacing of {1e3 * cover:.3g} mm, 2 Rmax)")
    return RebarLayout(ratio=float(ratio), n_bars=int(n_bars), y_m=ys, thickness_m=float(ratio) * h / n_bars, radius_m=r,
                       n_discs=n_discs, young=float(young), yield_stress=float(yield_stress))


def carve(assembly, lay):
    """The assembly without the discs that overlap a bar (their centre closer to the bar's line
    than their radius plus the bar discs' radius)."""
    over = np.zeros(assembly.n_particles, dtype=bool)
    for y in lay.y_m:
        over |= np.abs(assembly.y - y) < assembly.r + lay.radius_m
    return assembly.without(np.flatnonzero(over))


class Bars:
    """The bars of a scene: their disc ids, STEEL contacts and readings."""

    def __init__(self, lay, disc_ids, steel_pairs, area_m2, n_bond):
        self.layout, self.disc_ids, self.steel_pairs, self.area_m2 = lay, disc_ids, steel_pairs, area_m2
        self.n_bond = n_bond  # bond contacts made at the set-up
        self.yield_day = None

    def stresses(self):
        """Axial stress [Pa] of every STEEL contact (tension positive), bar after bar."""
        yade, _ = sc.require("swelldem.dem.rebar")
        O = yade.Omega()
        return np.array([O.interactions[i, j].phys.Fn for i, j in self.steel_pairs]) / self.area_m2

    def record(self, time_days):
        """(largest, mean) bar stress now [Pa]; notes the first time the largest reaches the yield
        stress. The mean over a bar's contacts is E_s times the bar's elongation over its length;
        the largest also carries the disc-scale fluctuations of the concrete the bar is bonded to."""
        s = self.stresses()
        if self.yield_day is None and s.max() >= self.layout.yield_stress:
            self.yield_day = float(time_days)
        return float(s.max()), float(s.mean())


def bond_kind(itz_kind, params=None):
    """The BOND ContactKind: a full copy of the ITZ kind `itz_kind` (its temperature too, for creep
    at temperature: docs/temperature.md), not swelling, with the ContactKind attributes of
    `params` ({attribute: value}, e.g. {'tensileStrength': 0.5e6} [Pa]) over it; the constructor
    checks every value."""
    params = dict(params or {})
    for fixed in ("name", "kindId"):  # what makes it the BOND kind
        if fixed in params:
            options.bad(f"BOND.{fixed}", params[fixed], f"left out (the BOND kind's {fixed} is {BOND if fixed == 'name' else paper.STRUCTURE_KIND_IDS[BOND]})")
    _, W = sc.require("swelldem.dem.rebar")
    return W.ContactKind(**{**itz_kind.dict(), "name": BOND, "kindId": paper.STRUCTURE_KIND_IDS[BOND], "swelling": False,
                            "swellDispInf": 0.0, **params})


def add_bars(assembly, yscene, lay, itz_kind, bond_params=None):
    """Adds the bars of `lay` to the scene that swelldem.dem.to_yade made from the carved assembly
    (before the run); itz_kind: the scenario's ITZ kind, whose parameters the BOND kind takes
    (swelling off), with the attributes of bond_params over them (bond_kind). Returns a Bars."""
    yade, W = sc.require("swelldem.dem.rebar")
    O = yade.Omega()
    from .scene import contact_kind
    ip2 = yscene.ip2
    b = float(assembly.thickness_m)
    area = lay.thickness_m * b
    # kn = E_s A / L, with A set to the bar's section A_s below
    ip2.steel = contact_kind(STEEL, behaviour="elastic", young=lay.young, shear_ratio=0.3, damage=False)
    ip2.bond = bond_kind(itz_kind, bond_params)
    mat = W.ConcreteMat(steel=True, young=lay.young, label="steel")
    O.materials.append(mat)
    rr, n = lay.radius_m, lay.n_discs
    band = 1.5 * float(assembly.r.max())
    ids, steel_pairs, n_bond = [], [], 0
    ip2.cohesive = True
    try:
        for y in lay.y_m:
            bar = [O.bodies.append(sc.disc((rr * (2 * k + 1), y), rr, mat)) for k in range(n)]
            ids += bar
            for k in range(n - 1):
                I = yade.utils.createInteraction(bar[k], bar[k + 1])
                I.phys.area = area
                steel_pairs.append((bar[k], bar[k + 1]))
            xb = rr * (2 * np.arange(n) + 1)
            # the discs that face the bar on each side (as a platen's: swelldem.dem.platens.facing_discs)
            above, below = np.flatnonzero(assembly.y > y), np.flatnonzero(assembly.y < y)
            near = np.concatenate([above[facing_discs(-assembly.y[above], assembly.x[above], assembly.r[above], band)],
                                   below[facing_discs(assembly.y[below], assembly.x[below], assembly.r[below], band)]])
            for j in near:
                m = int(np.argmin(np.abs(xb - assembly.x[j])))
                yade.utils.createInteraction(bar[m], int(yscene.ids[j]))
                n_bond += 1
    finally:
        ip2.cohesive = False
    return Bars(lay, ids, steel_pairs, area, n_bond)
