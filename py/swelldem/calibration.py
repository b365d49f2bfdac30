# SPDX-License-Identifier: GPL-2.0-or-later
"""Calibration of the swelling kinetics against a laboratory expansion curve (scripts/fit_kinetics.py).

What is fitted: the three swelling parameters a user cannot measure on the specimen's materials,
Larive's tau_c and tau_L [day] of the swelling kinds (ContactKind tauC, tauL) and the ultimate
free swelling strain eps_inf [-] of the swelling phase (d_inf = eps_inf x 2 R_mean). Each
evaluation of the model is a real specimen run (scripts/swelling_test.py through swelldem.study),
so the fitted values include the mesostructure's restraint, creep and, if on, damage.

Method: scipy.optimize.least_squares (trust-region reflective) on the logarithms of the three
values (they are positive and span decades), residuals the model's expansion minus the data at
the data's days, over the data's largest expansion. The Jacobian is a forward difference of
relative step fd_step: a point's three neighbours are run together with it, in parallel on the
study's workers, so an iteration costs about two run times on two workers. A Levenberg-Marquardt
or a derivative-free method would not use the workers better; a posterior (emcee) would need
thousands of runs. Uncertainty: the covariance s^2 (J^T J)^-1 of the least-squares Jacobian
(s^2 the residuals' variance), and, with several seeds, the spread of the values refitted on each
seed's mesostructure.

Plain Python (numpy, scipy); the runs go through swelldem.study.
"""
import csv
import hashlib
import math
import re

import numpy as np

from . import options, paper

#: The expansion units a curve's header may state, and their factor to [-].
UNITS = {"-": 1.0, "1": 1.0, "1e-6": 1e-6, "um/m": 1e-6, "µm/m": 1e-6, "%": 1e-2, "mm/m": 1e-3, "1e-3": 1e-3}
#: A fit whose residuals' RMS exceeds this share of the data's largest expansion is reported poor.
POOR_FIT_RMS = 0.05
#: A curve falling by more than this share of its maximum after it is refused: the model's
#: expansion (swelling, creep, damage) never decreases.
FALL_MAX = 0.2
#: Names of the fitted values, in the order of the parameter vector.
NAMES = ("tau_c", "tau_L", "eps_inf")
UNIT_OF = {"tau_c": "day", "tau_L": "day", "eps_inf": "-"}


def read_curve(path):
    """(days [day], expansion [-]) of a laboratory curve: a CSV whose header names the columns with
    units, 'day' (or 'time [day]') and e.g. 'expansion [1e-6]' (units: UNITS), then rows of numbers;
    '#' starts a comment. Refused in the one message form: days not finite, negative or not
    strictly increasing, fewer than 4 points (three values to fit), expansion not finite, no
    positive expansion, or a curve that falls by more than FALL_MAX of its maximum after it."""
    try:
        with open(path, newline="") as f:
            rows = [r for r in csv.reader(line for line in f if line.strip() and not line.lstrip().startswith("#"))]
    except OSError as e:
        options.bad("data", path, f"a readable CSV file ({e.strerror})")
    if not rows or len(rows[0]) < 2:
        options.bad("data", path, "a CSV with a header 'day, expansion [unit]' and rows of two numbers")
    head = [h.strip() for h in rows[0]]
    if not re.match(r"^(day|days|time \[(day|d)\]|day \[(day|d)\]|t \[(day|d)\])$", head[0], flags=re.I):
        options.bad("data header", head[0], "day (or time [day]): the first column holds days")
    m = re.search(r"\[([^\]]+)\]\s*$", head[1])
    if not m or m.group(1).strip() not in UNITS:
        options.bad("data header", head[1], f"the expansion with its unit in brackets, one of {', '.join(f'[{u}]' for u in UNITS)}")
    scale = UNITS[m.group(1).strip()]
    t, y = [], []
    for number, r in enumerate(rows[1:], start=2):
        try:
            t.append(float(r[0]))
            y.append(float(r[1]) * scale)
        except (ValueError, IndexError):
            options.bad("data row", f"{path}: row {number}: {','.join(r)}", "two numbers: day, expansion")
    t, y = np.array(t), np.array(y)
    if len(t) < 4:
        options.bad("data points", len(t), "at least 4 (three values are fitted)")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        options.bad("data", path, "finite days and expansions")
    if t[0] < 0:
        options.bad("data days", float(t[0]), "days >= 0")
    if np.any(np.diff(t) <= 0):
        i = int(np.argmax(np.diff(t) <= 0))
        options.bad("data days", f"{t[i]:g} then {t[i + 1]:g}", "strictly increasing days")
    top = float(y.max())
    if top <= 0:
        options.bad("data expansion", top, "a curve that expands (its largest value > 0)")
    fall = top - float(y[int(np.argmax(y)):].min())
    if fall > FALL_MAX * top:
        options.bad("data expansion", f"falls by {fall / top:.0%} after its maximum",
                    f"a curve that does not fall by more than {FALL_MAX:.0%} of its maximum (the model's expansion never decreases)")
    return t, y


def start_values(t, y, factor=1.0):
    """A first guess of (tau_c, tau_L, eps_inf) from the curve's shape: Larive's sigmoid goes from a
    quarter to three quarters of its plateau in 2 ln 3 tau_c around tau_L; eps_inf = the largest
    expansion / factor (the specimen's expansion over the free one, about 0.9)."""
    top = float(y.max())
    t_q = [float(np.interp(q * top, np.maximum.accumulate(y), t)) for q in (0.25, 0.5, 0.75)]
    tau_c = max((t_q[2] - t_q[0]) / (2 * math.log(3)), 1e-3 * max(t[-1], 1.0))
    tau_l = max(t_q[1], 1e-3 * max(t[-1], 1.0))
    return np.array([tau_c, tau_l, top / factor])


def kinetic_kinds(scenario):
    """The kinds that carry the swelling kinetics: the scenario's swelling kinds, the aggregate's
    gel pockets for asr-coarse."""
    return paper.SCENARIOS[scenario]["swelling_kinds"] or ("AGG",)


def run_settings(base, p, seed, days=()):
    """The swelling test's fields of an evaluation at p = (tau_c, tau_L, eps_inf): `base` (scenario,
    size, behaviour, ...) with the kinetic kinds' tauC and tauL, eps_inf and the seed; the solver
    also stops at the data's `days` within the run (its extraTimes), so that the model is compared
    at the days measured, not interpolated between its log-time steps."""
    kp = {k: dict(v) for k, v in (base.get("kind_params") or {}).items()}
    for kind in kinetic_kinds(base.get("scenario", "isr")):
        kp.setdefault(kind, {}).update(tauC=float(p[0]), tauL=float(p[1]))
    settings = {**base, "kind_params": kp, "eps_inf": float(p[2]), "seed": seed}
    inside = [float(d) for d in days if base["t_start_days"] < d < base["t_end_days"]]
    if inside:
        settings["solver_params"] = {**(base.get("solver_params") or {}), "extraTimes": inside}
    return settings


def run_name(p, seed, days=()):
    """A run's folder name: its values rounded, and a hash of the exact ones and the data's days
    (two evaluations never share a folder, and a resumed fit finds its runs)."""
    h = hashlib.sha1(repr((tuple(float(v) for v in p), tuple(float(d) for d in days))).encode()).hexdigest()[:8]
    return f"tc{p[0]:.4g}_tl{p[1]:.4g}_e{p[2]:.4g}_{h}-s{seed}"


def model_curve(res, t):
    """A run's linear expansion [-] at days t: the mean of its axes' strains (x, y; x, y, z in 3D),
    linear in log time between its steps, 0 up to its start."""
    axes = ("x", "y", "z") if res.get("dim") == 3 else ("x", "y")
    strain = np.mean([res[f"swelling_strain_{a}"] for a in axes], axis=0)
    days = np.asarray(res["times_days"], dtype=float)
    t0 = float(res["config"]["t_start_days"])
    lt = np.log(np.concatenate(([t0], days)))
    ys = np.concatenate(([0.0], strain))
    t = np.asarray(t, dtype=float)
    return np.where(t <= t0, 0.0, np.interp(np.log(np.maximum(t, t0)), lt, ys))


class Fit:
    """A least-squares fit of (tau_c, tau_L, eps_inf) to (t, y) for one seed. evaluate(list of p)
    -> list of model curves at t (runs made in parallel); fd_step: the Jacobian's relative step."""

    def __init__(self, t, y, evaluate, fd_step=0.05):
        self.t, self.y, self.evaluate, self.h = t, y, evaluate, math.log1p(fd_step)
        self.scale = float(np.max(np.abs(y)))
        self.cache = {}
        self.evaluations = 0

    def _curves(self, xs):
        need = [x for x in xs if tuple(x) not in self.cache]
        if need:
            for x, c in zip(need, self.evaluate([np.exp(x) for x in need])):
                self.cache[tuple(x)] = np.asarray(c, dtype=float)
            self.evaluations += len(need)
        return [self.cache[tuple(x)] for x in xs]

    def _neighbours(self, x):
        return [x] + [x + self.h * e for e in np.eye(len(x))]

    def residuals(self, x):
        # the point and its Jacobian's neighbours together: the workers run them side by side
        return (self._curves(self._neighbours(np.asarray(x, dtype=float)))[0] - self.y) / self.scale

    def jacobian(self, x):
        c = self._curves(self._neighbours(np.asarray(x, dtype=float)))
        return np.column_stack([(ci - c[0]) / self.scale / self.h for ci in c[1:]])

    def run(self, p0, max_nfev=25):
        """Fits from p0; returns the record: values, their 1-sigma relative (log) uncertainty from
        the Jacobian, residuals, RMS over the largest expansion, evaluations, the optimiser's status."""
        from scipy.optimize import least_squares
        sol = least_squares(self.residuals, np.log(p0), jac=self.jacobian, method="trf", xtol=1e-3, ftol=1e-4, gtol=1e-6,
                            max_nfev=max_nfev)
        r = self.residuals(sol.x)
        J = self.jacobian(sol.x)
        dof = max(len(r) - len(sol.x), 1)
        s2 = float(r @ r) / dof
        try:
            cov = s2 * np.linalg.inv(J.T @ J)
            sig = np.sqrt(np.clip(np.diag(cov), 0, None))
        except np.linalg.LinAlgError:  # a value the curve does not determine
            sig = np.full(len(sol.x), np.inf)
        p = np.exp(sol.x)
        curve = r * self.scale + self.y
        return {"values": dict(zip(NAMES, p.tolist())), "log_sigma": dict(zip(NAMES, sig.tolist())),
                "model": curve.tolist(), "residuals": (curve - self.y).tolist(),
                "rms_relative": float(math.sqrt(float(r @ r) / len(r))), "evaluations": self.evaluations,
                "optimizer": {"status": int(sol.status), "message": str(sol.message), "nfev": int(sol.nfev),
                              "njev": int(sol.njev or 0), "start": dict(zip(NAMES, np.asarray(p0, dtype=float).tolist()))}}


def combine(fits):
    """The fitted values over seeds: per value the mean, the Jacobian's 1-sigma (relative, the
    seeds' mean), the seeds' spread (relative standard deviation of the values; 0 for one seed)
    and the total 1-sigma sqrt(jacobian^2 + seeds^2), with the 95 % interval value x exp(+-2 sigma)."""
    out = {}
    for n in NAMES:
        v = np.array([f["values"][n] for f in fits])
        lj = float(np.mean([f["log_sigma"][n] for f in fits]))
        ls = float(np.std(np.log(v), ddof=1)) if len(v) > 1 else 0.0
        lt = math.hypot(lj, ls)
        mean = float(np.exp(np.mean(np.log(v))))
        out[n] = {"value": mean, "unit": UNIT_OF[n], "sigma_jacobian_rel": lj, "sigma_seeds_rel": ls, "sigma_rel": lt,
                  "low95": mean * math.exp(-2 * lt), "high95": mean * math.exp(2 * lt), "per_seed": v.tolist()}
    return out
