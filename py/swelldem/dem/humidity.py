# SPDX-License-Identifier: GPL-2.0-or-later
"""Moisture in a YADE scene: the relative humidity h of swelldem.moisture drives each contact's
swelling and drying shrinkage.

The transport does not depend on the mechanics (cracks do not change the conduits,
docs/moisture.md), so the whole h history is computed before the run, on the solver's own
physical times (LogTimeSolver.plannedTimes) split into at least `steps_per_decade` moisture steps a
decade (backward Euler's time error: about 1 % of the drop at 40 a decade, docs/moisture.md
section 5). Before each physical step the driver sets two settings of every contact that uses them
(SwellPhys.swellFactor and imposedOpening); the contact law applies them when the step sets the
contact up (after the solver's stepHook), so both solvers see the same loads.

- A contact's h (contact_h): the mean of its two particles' h; an ITZ contact takes its mortar
  particle's (the interfacial zone is cement paste, whose water is the mortar's).
- Swelling: the increment of a step from t_{k-1} to t_k is d_inf f dxi with f the mean of f(h)
  over the step's moisture substeps weighted by the swelling each sees (the trapezoidal rule in
  xi), f(h) = h^m (Capra and Bournazel's form, used
  by Saouma and Perotti 2006). Gel formed in wet steps stays when the contact dries later.
- Drying shrinkage: the imposed free opening at t_k is -k_sh L (h_c(t_start) - h_c(t_k)), L the
  contact's length, k_sh its kind's coefficient [strain per unit of h]: the drop of h since the
  stress-free start, recovered on wetting (no irreversible part).
With h = 1 everywhere and no face exposed every factor is 1 and every imposed opening 0: the run
is the saturated one bit for bit.
"""
import math
from dataclasses import dataclass

import numpy as np

from .. import moisture, paper
from ..plugin import require

#: Drying-shrinkage coefficient k_sh of each kind [strain per unit of h] (docs/moisture.md section 10).
DEFAULT_SHRINKAGE = {"MORTAR": 2.2e-3, "ITZ": 2.2e-3, "AGG": 0.0}

#: Faces of a specimen, in swelldem.moisture's names.
FACES_2D = ("x-", "x+", "y-", "y+")
FACES_3D = FACES_2D + ("z-", "z+")


def _yade():
    return require("swelldem.dem.humidity")


def substeps(times, steps_per_decade, breakpoints=()):
    """The moisture grid of physical times `times` [day]: each interval split geometrically into
    ceil(steps_per_decade x its decades) steps (linearly from t = 0), and split again at every
    breakpoint inside it (the days of an ambient history: a wet spell between two steps is not
    stepped over). Returns (grid, index of each time of `times` in grid)."""
    breaks = np.unique(np.asarray(breakpoints, dtype=float))
    grid, index = [float(times[0])], [0]
    for a, b in zip(times[:-1], times[1:]):
        if a > 0:
            n = max(1, math.ceil(steps_per_decade * math.log10(b / a) - 1e-9))
            pts = a * (b / a) ** (np.arange(1, n) / n)
        else:
            n = max(1, math.ceil(steps_per_decade))
            pts = a + (b - a) * np.arange(1, n) / n
        inner = breaks[(breaks > a * (1 + 1e-9)) & (breaks < b * (1 - 1e-9))]
        pts = np.unique(np.concatenate([pts, inner]))
        grid.extend(pts.tolist() + [float(b)])
        index.append(len(grid) - 1)
    return np.array(grid), np.array(index)


@dataclass
class Coupling:
    """How h acts on the contacts: exponent [-] of f(h) = h^m on the swelling increment, and the
    drying-shrinkage coefficient k_sh [strain per unit of h] of each kind (absent: 0)."""
    exponent: float
    shrinkage: dict

    def swelling_factor(self, h):
        return np.asarray(h, dtype=float) ** self.exponent


def contact_h(h, i, j, itz, mortar_end):
    """h [-] of contacts (i, j) from their particles' h (rows: times): the mean of the two, and for
    an ITZ contact (itz) the h of its mortar particle (mortar_end)."""
    hc = 0.5 * (h[:, i] + h[:, j])
    hc[:, itz] = h[:, mortar_end[itz]]
    return hc


def step_factor(f, w):
    """One step's swelling factor: f [-] at the step's moisture times (rows; a column per contact)
    averaged by the trapezoidal rule in w (xi, or time), the increments of w [-] at those times
    (w increasing: equal weights where it does not). 1 - sum w (1 - f), so that f = 1 gives 1
    exactly."""
    f, w = np.asarray(f, dtype=float), np.asarray(w, dtype=float)
    dw = np.diff(w)
    total = dw.sum()
    share = dw / total if total > 0 else np.full(len(dw), 1.0 / len(dw))
    return 1.0 - share @ (1.0 - 0.5 * (f[:-1] + f[1:]))


class HumidityDriver:
    """The moisture of a built scene: its h history (MoistureNetwork.run on the solver's planned
    times, substepped) and, per physical step, the contacts' swelling factors and imposed
    openings. Call apply(step) before step `step` (1..nSteps) runs; as a stepHook it applies the
    solver's coming step. faces: {face: h or (days, h)}; h0: the initial h, one number or one per
    particle."""

    def __init__(self, assembly, yscene, solver, faces, h0, coupling, steps_per_decade=40.0, kinds=None, xi=None):
        self.solver, self.coupling, self.faces = solver, coupling, faces
        self.network = moisture.MoistureNetwork(assembly, kinds)
        self.times = np.array(solver.plannedTimes, dtype=float)
        breakpoints = [d for v in faces.values() if isinstance(v, (tuple, list)) for d in v[0]]
        grid, index = substeps(self.times, steps_per_decade, breakpoints)
        hist = self.network.run(grid, h0, faces)
        self.history = hist
        self.h = hist.h[index]  # (times, particles)
        self.volume = self.network.capacity_m3
        self.particle_kind = self.network.particle_kind
        pairs = np.asarray(yscene.contacts, dtype=np.int64).reshape(-1, 2)
        O = _yade()[0].Omega()
        phys = [O.interactions[int(i), int(j)].phys for i, j in pairs]
        self.kind = np.array([p.kindId for p in phys], dtype=np.int64)
        i, j = pairs[:, 0], pairs[:, 1]
        itz = self.kind == paper.KIND_IDS["ITZ"]
        mortar_end = np.where(np.asarray(assembly.aggregate_id)[i] < 0, i, j)
        self.h_contact = hc = contact_h(self.h, i, j, itz, mortar_end)
        ksh = np.zeros(len(phys))
        for name, k in coupling.shrinkage.items():
            ksh[self.kind == paper.KIND_IDS[name]] = k
        swells = np.array([p.swellingDispInf > 0 for p in phys])
        self.swelling = [p for p, s in zip(phys, swells) if s]
        self.shrinking = [p for p, k in zip(phys, ksh) if k > 0]
        self.factor = self._step_factors(hist.h, index, i[swells], j[swells], itz[swells], mortar_end[swells], grid, xi)
        sh = ksh > 0
        lengths = np.array([p.length for p in self.shrinking])
        self.opening = -ksh[sh] * lengths * (hc[0, sh] - hc[:, sh])  # per time: the total imposed opening [m]

    def _step_factors(self, h_grid, index, i, j, itz, mortar_end, grid, xi):
        """Per physical step and swelling contact, f averaged over the step's moisture substeps,
        each weighted by the swelling it sees: sum_s (f_s + f_(s+1))/2 (xi_(s+1) - xi_s) / (xi_end -
        xi_start), the trapezoidal rule in xi (xi: the swelling kinetics' xi(t) [-] of the run, a
        callable of days; none: weights in time). Written 1 - sum w (1 - f) so that f = 1 gives 1
        exactly (the saturated run bit for bit)."""
        weight_of = xi if xi is not None else (lambda t: np.asarray(t, dtype=float))
        w_grid = weight_of(grid)
        out = np.empty((len(index) - 1, len(i)))
        for k in range(len(index) - 1):
            s = slice(index[k], index[k + 1] + 1)
            out[k] = step_factor(self.coupling.swelling_factor(contact_h(h_grid[s], i, j, itz, mortar_end)), w_grid[s])
        return out

    @property
    def n_steps(self):
        return len(self.times) - 1

    def apply(self, step):
        """Sets the contacts' swelling factor and imposed opening for physical step `step` (from
        times[step - 1] to times[step]); nothing past the last step."""
        if not 1 <= step <= self.n_steps:
            return
        for p, f in zip(self.swelling, self.factor[step - 1].tolist()):
            p.swellFactor = f
        for p, u in zip(self.shrinking, self.opening[step].tolist()):
            p.imposedOpening = u

    def __call__(self):
        if not self.solver.finished:
            self.apply(int(self.solver.step))

    def mean_h(self):
        """Per time of `times`: the mean h of each contact kind's contacts and the volume-weighted
        mean h of the mortar and aggregate particles and of the specimen, {name: [h, ...]}."""
        out = {}
        for name in paper.KIND_NAMES:
            sel = self.kind == paper.KIND_IDS[name]
            if sel.any():
                out[f"{name}_contacts"] = self.h_contact[:, sel].mean(axis=1).tolist()
        for name in ("MORTAR", "AGG"):
            sel = self.particle_kind == paper.KIND_IDS[name]
            if sel.any():
                out[f"{name}_particles"] = (self.h[:, sel] @ self.volume[sel] / self.volume[sel].sum()).tolist()
        out["specimen"] = (self.h @ self.volume / self.volume.sum()).tolist()
        return out

    def h_at(self, t_days):
        """h of every particle at physical time t_days [day] (linear between the planned times)."""
        k = int(np.searchsorted(self.times, t_days))
        if k <= 0:
            return self.h[0]
        if k >= len(self.times):
            return self.h[-1]
        w = (t_days - self.times[k - 1]) / (self.times[k] - self.times[k - 1])
        return (1 - w) * self.h[k - 1] + w * self.h[k]


#: The h history of a run beside its results.json: times_days (planned times) and h (times,
#: particles), float32 (a drawing's precision; results.json has the means in double).
HISTORY_FILE = "humidity.npz"


def save_history(out, driver):
    """HISTORY_FILE in `out` from a driver."""
    import os
    np.savez_compressed(os.path.join(out, HISTORY_FILE), times_days=driver.times, h=driver.h.astype(np.float32))
