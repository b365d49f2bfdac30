# SPDX-License-Identifier: GPL-2.0-or-later
"""Residual properties of a swollen specimen: virtual mechanical tests at chosen ages of a swelling
run, next to the same tests on the undamaged specimen of the same age (issue 16).

What a virtual test is (docs/residual-properties.md gives the reasons):

* It runs on a copy of the swelling run's scene, saved with ``O.save`` by :class:`AgeSaver` in the
  run's per-step hook at the test age (the age is added to the run's schedule, ``extraTimes``).
  The run itself goes on untouched; the tests load the saved file afterwards.
* A laboratory test lasts minutes: during it the concrete neither creeps nor swells. Each contact
  keeps its forces and broken state and is loaded further with the static modulus of its kind at
  the test age, E(t) = 1/J(t + 0.01 d, t) of its B3 q's (the 'aging-elastic' behaviour of the
  scenarios; aggregate contacts keep their constant modulus), its strength unchanged
  (:func:`kinds_for_test`). Viscoelastic kinds become aging-elastic for the test: their creep history
  (the Kelvin-chain strains) stays stored and unused.
* Loading: displacement control between two bands of discs (those whose edge lies within
  1.5 Rmax of the left or right side, :func:`swelldem.dem.uniaxial.bands`), both held in x, one
  left disc also in y; the right band is moved by one strain increment per physical step of the
  ADR (the solver's quasi-static equilibria, breaks at equilibrium); lateral faces free,
  frictionless platens (y free). Stress = mean band reaction / (H b) [Pa], strain = band
  displacement / W [-]; compression counted positive in the compression and SDT results.
* Tests: 'tension' and 'compression' to past the peak (peak stress; modulus = least-squares slope
  of the first loading branch over MODULUS_WINDOW of the peak stress); a compression test
  usually ends when a step past the peak finds no equilibrium (the specimen has failed: status
  'no_equilibrium'), its normal end; one that stops while the stress still rises has a peak that
  is only a lower bound of the strength (peak_is_lower_bound); 'sdt', the stiffness
  damage test: SDT_CYCLES load-unload cycles in compression to a fraction of the undamaged
  specimen's compressive strength, stiffness damage index SDI = hysteresis (dissipated) energy /
  loading (total) energy summed over the cycles, plastic strain index PDI = strain left at zero
  load after the last cycle / largest strain of the cycles (:func:`sdt_indices`).

Run inside YADE with the plugin (scripts/yade-swelldem); :func:`sdt_indices`, :func:`modulus_fit`
and :func:`check_request` are plain numpy / Python.
"""
import math
import os

import numpy as np

TESTS = ("tension", "compression", "sdt")
#: Stress range of the modulus fit, as fractions of the peak stress of the test (first loading
#: branch). The lower bound skips nothing physical in a quasi-static test; it follows ASTM C469's
#: chord, which starts just above zero load, and the upper is its 40 % of the strength.
MODULUS_WINDOW = (0.05, 0.40)
#: Load duration of the static modulus of the B3 compliance (Bazant & Baweja 1995) [day]; the
#: plugin's aging-elastic kinds use it: E(t) = 1/J(t + 0.01, t).
STATIC_LAG_DAYS = 0.01
#: The physical time a test spans, as a fraction of its age: its steps need distinct times, and
#: aging over it stays below this fraction of the modulus' own change with age [-].
TEST_SPAN = 1e-4
SDT_CYCLES = 5
SDT_FRACTION = 0.4
#: ContactKind attributes that are results of a run, not parameters (not copied to a test kind).


def _bad(option, value, allowed):
    raise ValueError(f"swelldem: {option} = {value} is out of range; allowed: {allowed}")


def check_request(test_ages, t_start, t_end, tests, sdt_fraction, sdt_cycles=SDT_CYCLES):
    """ValueError in the form '<option> = <value> is out of range; allowed: <range>' for ages
    outside (t_start, t_end] [day], unknown tests, an SDT fraction outside (0, 1) or a cycle count < 1."""
    if not test_ages:
        _bad("--test-ages", "(none)", f"one or more ages in ({t_start:g}, {t_end:g}] days")
    for a in test_ages:
        if not (t_start < a <= t_end) or not math.isfinite(a):
            _bad("--test-ages", f"{a:g}", f"ages in ({t_start:g}, {t_end:g}] days (after the stress-free start, up to the run's end)")
    if len(set(test_ages)) != len(test_ages):
        _bad("--test-ages", " ".join(f"{a:g}" for a in test_ages), "distinct ages")
    for t in tests:
        if t not in TESTS:
            _bad("--tests", t, ", ".join(TESTS))
    if not (0 < sdt_fraction < 1):
        _bad("--sdt-fraction", f"{sdt_fraction:g}", "0 < fraction < 1 (of the undamaged specimen's compressive strength)")
    if not (isinstance(sdt_cycles, int) and sdt_cycles >= 1):
        _bad("--sdt-cycles", sdt_cycles, "an integer >= 1")


def modulus_fit(strain, stress, peak, window=MODULUS_WINDOW):
    """Slope [Pa] of the least-squares line through the points of the first loading branch (up to
    the peak) whose stress lies in window x peak; nan with fewer than 2 points."""
    strain, stress = np.asarray(strain, float), np.asarray(stress, float)
    upto = int(np.argmax(stress)) + 1
    s, e = stress[:upto], strain[:upto]
    sel = (s >= window[0] * peak) & (s <= window[1] * peak)
    if sel.sum() < 2:
        return float("nan")
    return float(np.polyfit(e[sel], s[sel], 1)[0])


def sdt_indices(strain, stress, branch):
    """SDT output from a recorded cycle history: strain [-], stress [Pa] (compression positive)
    and branch (per point: +k while loading in cycle k, -k while unloading it, 0 the start).
    Returns SDI = sum of the hysteresis areas / sum of the loading areas [-], PDI = strain at the
    end of the last unloading / largest strain [-], the per-cycle energies [J/m3] and the secant
    modulus of each loading branch [Pa]."""
    e, s, b = (np.asarray(v, float) for v in (strain, stress, branch))
    cycles = sorted({int(k) for k in b if k > 0})
    w_load, w_unload, secant = [], [], []
    for k in cycles:
        # each branch includes the point where the previous one ended
        il = np.flatnonzero(b == k)
        iu = np.flatnonzero(b == -k)
        il = np.concatenate([[il[0] - 1], il]) if il[0] > 0 else il
        wl = float(np.trapz(s[il], e[il]))
        w_load.append(wl)
        secant.append(float((s[il[-1]] - s[il[0]]) / (e[il[-1]] - e[il[0]])) if e[il[-1]] != e[il[0]] else float("nan"))
        if len(iu):
            iu = np.concatenate([[iu[0] - 1], iu])
            w_unload.append(float(-np.trapz(s[iu], e[iu])))
        else:
            w_unload.append(float("nan"))
    wl, wu = np.array(w_load), np.array(w_unload)
    done = np.isfinite(wu)
    sdi = float(np.sum(wl[done] - wu[done]) / np.sum(wl[done])) if done.any() else float("nan")
    last_unload = np.flatnonzero(b == -cycles[-1]) if cycles else []
    pdi = float("nan")
    if len(last_unload) >= 2 and e.max() > 0:
        # the strain at zero stress, interpolated on the last unloading step (which lands near zero, not on it)
        i, j = last_unload[-2], last_unload[-1]
        e0 = e[j] if s[i] == s[j] else e[i] + (0.0 - s[i]) * (e[j] - e[i]) / (s[j] - s[i])
        pdi = float(e0 / e.max())
    return {"SDI": sdi, "PDI": pdi, "cycles_done": int(done.sum()), "loading_energy_J_m3": w_load, "unloading_energy_J_m3": w_unload,
            "secant_modulus_Pa": secant}


# ---------------------------------------------------------------- inside YADE

def _yade():
    from .plugin import require
    return require("swelldem.residual")


def _solver():
    yade, _ = _yade()
    return [e for e in yade.Omega().engines if hasattr(e, "stepHook")][-1]


class AgeSaver:
    """A swelling run's after-step callable: at each of `ages` [day] (which must be stops of the
    run's schedule) saves the scene with O.save to out/state_<age>d.yade.gz. Saving reads the scene
    and changes nothing in it (tests/python/test_residual.py compares a run with and without)."""

    def __init__(self, ages, out):
        self.out = out
        self.pending = sorted(float(a) for a in ages)
        self.saved = {}

    @staticmethod
    def path(out, age):
        return os.path.join(out, f"state_{age:g}d.yade.gz")

    def __call__(self):
        yade, _ = _yade()
        t = _solver().physTime
        for a in list(self.pending):
            if abs(t - a) <= 1e-9 * a:
                p = self.path(self.out, a)
                yade.Omega().save(p)
                self.saved[a] = p
                self.pending.remove(a)


def scene_kinds():
    """{kindId: ContactKind} of the real SwellPhys contacts of O."""
    yade, _ = _yade()
    out = {}
    for I in yade.Omega().interactions:
        if I.isReal and hasattr(I.phys, "kind"):
            out.setdefault(I.phys.kind.kindId, I.phys.kind)
    return out


def kinds_for_test(kinds):
    """Test kinds for {kindId: ContactKind}: the same parameters, swelling off, viscoelastic made
    aging-elastic (same B3 q's: its short-term response E(t) = 1/J(t + 0.01 d, t)); 'elastic' and
    'aging-elastic' stay as they are."""
    _, W = _yade()
    out = {}
    for kid, k in kinds.items():
        attrs = k.dict()
        if attrs.get("behaviour") == "viscoelastic":
            attrs["behaviour"] = "aging-elastic"
        attrs["swelling"] = False
        attrs["swellDispInf"] = 0.0
        out[kid] = W.ContactKind(**attrs)
    return out


def swap_kinds(new):
    """Gives every real SwellPhys contact of O the kind of its kindId in `new` (the contacts take up
    their new kinds at the test solver's first step)."""
    yade, _ = _yade()
    for I in yade.Omega().interactions:
        if I.isReal and hasattr(I.phys, "kind"):
            I.phys.kind = new[I.phys.kind.kindId]


class _Loader:
    """The test solver's stepHook: after each converged step records (strain, stress, broken) and
    moves the right band by the next increment of the protocol (a list of legs)."""

    def __init__(self, O, assembly, mode, legs, n_idle, left, right, max_steps):
        self.O, self.a, self.mode, self.legs = O, assembly, mode, legs
        self.sign = 1.0 if mode == "tension" else -1.0
        self.n_idle, self.left, self.right, self.max_steps = n_idle, left, right, max_steps
        self.area = assembly.height_m * assembly.thickness_m
        self.calls = 0
        self.leg = 0
        self.strain, self.stress, self.branch, self.broken = [], [], [], []
        self.f0 = None
        self.x0 = None
        self.done = False
        self.status = "running"
        self.max_stress = 0.0
        self.k_tan = None
        self.branch_id = 0
        self.cycle = 0
        self.branch_max = 0.0

    def _measure(self):
        O = self.O
        xr = np.mean([O.bodies[int(i)].state.pos[0] for i in self.right])
        xl = np.mean([O.bodies[int(i)].state.pos[0] for i in self.left])
        fr = -sum(O.forces.f(int(i))[0] for i in self.right)
        fl = sum(O.forces.f(int(i))[0] for i in self.left)
        return xr - xl, 0.5 * (fr + fl)

    def _move(self, deps):
        dx = self.sign * deps * self.a.width_m
        yade, _ = _yade()
        for i in self.right:
            b = self.O.bodies[int(i)]
            b.state.pos = b.state.pos + yade.Vector3(dx, 0, 0)

    def _finish(self, status):
        self.done, self.status = True, status
        self.O.stopAtIter = self.O.iter + 1

    def __call__(self):
        self.calls += 1
        if self.calls < self.n_idle:
            return
        d, f = self._measure()
        if self.x0 is None:  # start of the loading: the reference state (the swollen specimen at rest)
            self.x0, self.f0 = d, f
        eps = self.sign * (d - self.x0) / self.a.width_m
        sig = self.sign * (f - self.f0) / self.area
        nb = sum(1 for I in self.O.interactions if I.isReal and I.phys.broken)
        if self.strain:
            de = eps - self.strain[-1]
            if abs(de) > 0:
                self.k_tan = (sig - self.stress[-1]) / de
        self.strain.append(eps)
        self.stress.append(sig)
        self.broken.append(nb)
        self.branch.append(self.branch_id)
        self.max_stress = max(self.max_stress, sig)
        if not math.isfinite(sig):
            return self._finish("diverged")
        if len(self.strain) > self.max_steps:
            return self._finish("max_steps")
        deps = self._next(eps, sig)
        if deps is None:
            return
        self._move(deps)

    def _next(self, eps, sig):
        while self.leg < len(self.legs):
            kind, step, arg = self.legs[self.leg]
            if kind == "peak":  # load until the stress has fallen below arg x peak after it, or strain `step[1]`
                deps, eps_max = step
                if self.branch_id == 0:
                    self.branch_id = 1
                past = self.max_stress > 0 and sig < arg * self.max_stress and self.stress.index(self.max_stress) < len(self.stress) - 1
                if past or eps >= eps_max:
                    self.leg += 1
                    continue
                return deps
            if kind == "load":  # SDT: load to stress `arg`
                if self.branch_id <= 0:
                    self.cycle += 1
                    self.branch_id = self.cycle
                    self.branch_max = sig
                self.branch_max = max(self.branch_max, sig)
                if sig >= 0.995 * arg:
                    self.leg += 1
                    continue
                if self.branch_max > 0 and sig < 0.8 * self.branch_max:  # past this specimen's own peak
                    return self._finish("failed_before_target")
                return self._step_to(step, arg - sig)
            if kind == "unload":  # SDT: unload to zero stress
                if self.branch_id > 0:
                    self.branch_id = -self.cycle
                if sig <= 0.005 * arg:
                    self.leg += 1
                    continue
                return -self._step_to(step, sig)
        self._finish("done")
        return None

    def _step_to(self, deps, remaining):
        # Land on the target: the last increment from the branch's current tangent, no smaller
        # than a tenth of the step (a flat tangent near a peak would ask for a huge one).
        if self.k_tan is not None and self.k_tan > 0 and self.branch[-1] == self.branch_id:
            return float(min(deps, max(0.1 * deps, 1.02 * remaining / self.k_tan)))
        return deps


def run_test(assembly, mode, legs, age_days, n_idle=0, max_steps=400, tolerance=1e-4, solver_name="adr", max_iterations=8000):
    """Runs a loading protocol on the scene in O (its contacts already of test kinds) at age
    age_days [day]: legs, a list of ('peak', (deps, eps_max), drop) or ('load', deps, target_Pa) /
    ('unload', deps, target_Pa); n_idle physical steps without load first; solver_name 'adr' or
    'implicit' (swelldem.dem.SOLVERS; measured: implicit 4x faster in tension, same modulus within
    0.3 %, but in compression it finds no equilibrium 12 % below the ADR's peak, docs/residual-properties.md).
    A step that finds no
    equilibrium within max_iterations ends the test with status 'no_equilibrium': past the peak
    in compression, broken contacts sliding under the imposed shortening form a mechanism that the
    ADR follows without end (the specimen has failed). Returns a dict: strain, stress_Pa, branch,
    broken (per converged step), status, iterations, steps."""
    import time
    from .dem import make_solver
    from .dem.uniaxial import bands
    yade, _ = _yade()
    O = yade.Omega()
    left, right = bands(assembly)
    for i in np.concatenate([left, right]):
        O.bodies[int(i)].state.blockedDOFs = "xzXY"
    O.bodies[int(left[np.argmin(assembly.y[left])])].state.blockedDOFs = "xyzXY"
    n = n_idle + max_steps + 2
    span = TEST_SPAN * age_days
    extra = (age_days + span * np.arange(1, n) / n).tolist()
    settings = dict(tStart=age_days, tEnd=age_days + span, stepsPerDecade=1e-3, extraTimes=extra, maxIterations=max_iterations,
                    verbose=False, label="residualSolver")
    if tolerance is not None:  # None: the solver's own (its class's default)
        settings["tolerance"] = tolerance
    solver = make_solver(solver_name, **settings)
    engines = [e for e in O.engines if not hasattr(e, "stepHook")]
    O.engines = engines + [solver]
    loader = _Loader(O, assembly, mode, legs, n_idle, left, right, max_steps)
    solver.stepHook = loader
    t0 = time.time()
    drive_test(solver, loader)
    return {"mode": mode, "strain": loader.strain, "stress_Pa": loader.stress, "branch": loader.branch, "broken": loader.broken,
            "status": loader.status, "iterations": int(solver.totalIterations), "steps": len(loader.strain), "wall_s": time.time() - t0,
            "tolerance": float(solver.tolerance)}


def drive_test(solver, loader, step_iterations=None):
    """Runs a loading test's solver until its loader (the stepHook, with attributes done and status)
    ends it. A step that finds no equilibrium ends it with status 'no_equilibrium': within the
    solver's maxIterations, or, with step_iterations, within that many iterations after
    loader.it0 (the total iterations at its last converged step), for a step whose rounds of breaks
    go on without reaching maxIterations soon (the specimen has failed). A schedule that ends first
    leaves status 'schedule_end'."""
    from .dem import run_chunk_quietly
    try:
        while not loader.done and not solver.finished:
            # a test past its peak ends by 'no equilibrium': expected, so without YADE's FATAL lines
            run_chunk_quietly(solver, 2000)
            if step_iterations and not loader.done and int(solver.totalIterations) - loader.it0 > step_iterations:
                loader.done, loader.status = True, "no_equilibrium"
    except RuntimeError as e:
        if "no equilibrium" not in str(e):
            raise
        loader.done, loader.status = True, "no_equilibrium"
    if not loader.done:
        loader.status = "schedule_end"


def peak_is_lower_bound(stress):
    """Whether the highest stress [Pa] of a test's converged steps is only a lower bound of its
    strength: it is the last one, so the test stopped (no equilibrium, or its step budget spent)
    while the stress was still rising, before its peak showed."""
    s = np.asarray(stress, float)
    return bool(len(s) == 0 or int(np.argmax(s)) == len(s) - 1)


def strength_result(res):
    """Peak [Pa], strain at peak, modulus [Pa] (MODULUS_WINDOW) of a 'peak' test, and
    'peak_lower_bound' (peak_is_lower_bound: the peak is a lower bound of the strength)."""
    s = np.asarray(res["stress_Pa"])
    e = np.asarray(res["strain"])
    k = int(np.argmax(s))
    peak = float(s[k])
    return {"peak_Pa": peak, "peak_lower_bound": peak_is_lower_bound(s), "strain_at_peak": float(e[k]), "modulus_Pa": modulus_fit(e, s, peak),
            "broken_at_peak": int(res["broken"][k]), "broken_start": int(res["broken"][0]), "broken_end": int(res["broken"][-1])}


def strength_legs(mode, deps, eps_max):
    """The protocol of a strength test: load past the peak (stop below 50 % of it in tension, 85 %
    in compression, where each step past the peak costs the ADR most, or at eps_max)."""
    return [("peak", (deps, eps_max), 0.5 if mode == "tension" else 0.85)]


def sdt_legs(deps, target_Pa, cycles=SDT_CYCLES):
    """The SDT protocol: `cycles` times, load to target_Pa [Pa] and unload to zero stress, with
    strain increments deps [-] (the last of each branch shortened to land on its target)."""
    legs = []
    for _ in range(cycles):
        legs += [("load", deps, target_Pa), ("unload", deps, target_Pa)]
    return legs


def load_copy(path):
    """Loads a saved swelling state into O and swaps its contacts to test kinds (run_test puts the
    test solver in place of the swelling run's)."""
    yade, _ = _yade()
    yade.Omega().load(path)
    swap_kinds(kinds_for_test(scene_kinds()))


def fresh_specimen(assembly, kinds_by_name):
    """The undamaged specimen: the assembly as a new scene with test kinds made from kinds_by_name
    ({'MORTAR': ContactKind, ...})."""
    from . import dem, paper
    tk = kinds_for_test({paper.KIND_IDS[n]: k for n, k in kinds_by_name.items()})
    dummy = dem.make_solver("adr", verbose=False)
    dem.to_yade(assembly, {n: tk[paper.KIND_IDS[n]] for n in kinds_by_name}, dummy)


#: The residual ratios plot_against_expansion draws: key of a residual.csv row -> (label, marker).
RATIOS = {"E_rel": ("$E/E_0$ (compression modulus)", "o"), "fc_rel": ("$f_c/f_{c0}$", "s"), "ft_rel": ("$f_t/f_{t0}$", "D")}


def plot_against_expansion(path, rows, title):
    """residual_vs_expansion.png: the ages of one run (rows: residual.csv's rows as dicts) against
    their linear expansion [%] (expansion_linear_pct): left E/E0, f_c/f_c0 and f_t/f_t0 [-], a
    strength ratio whose strength is a lower bound (its <key>_lower_bound flag, the swollen
    specimen's or the reference's) drawn open and named so; right the SDI [-] of the swollen
    specimen, and the undamaged reference's (the method's floor), where the SDT did all its cycles.
    Each point labelled with its age [day]."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x = np.array([r["expansion_linear_pct"] for r in rows], float)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.3))
    for k, (key, (label, marker)) in enumerate(RATIOS.items()):
        if not any(key in r for r in rows):
            continue
        y = np.array([r.get(key, np.nan) for r in rows], float)
        q = key.split("_")[0]
        low = np.array([bool(r.get(f"{q}_lower_bound") or r.get(f"{q}0_lower_bound")) for r in rows])
        c = f"C{k}"
        ax.plot(x, y, "-", color=c, lw=1, alpha=0.6)
        if (~low).any():
            ax.plot(x[~low], y[~low], marker, color=c, ls="none", label=label)
        if low.any():
            ax.plot(x[low], y[low], marker, mfc="white", color=c, ls="none",
                    label=f"{label}: its swollen or undamaged strength is a lower bound\n(the test stopped before its peak)")
    for xi, r in zip(x, rows):
        ax.annotate(f"{r['age_days']:g} d", (xi, 1.0), textcoords="offset points", xytext=(0, 4), ha="center", fontsize=7, color="0.35")
    ax.axhline(1.0, color="0.6", lw=0.8)
    ax.set(xlabel="linear expansion at the test age, mean of the x and y strains [%]", ylabel="swollen / undamaged at the same age [-]",
           title="residual stiffness and strength")
    ax.set_ylim(0, max(1.15, np.nanmax([r.get(k, np.nan) for r in rows for k in RATIOS] + [1.0]) + 0.05))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
    done = np.array([r.get("sdt_status") == "done" for r in rows])
    if any("SDI" in r for r in rows):
        sdi = np.array([r.get("SDI", np.nan) for r in rows], float)
        sdi0 = np.array([r.get("SDI0", np.nan) for r in rows], float)
        bx.plot(x[done], sdi[done], "o-", color="C3", label="SDI, swollen specimen")
        bx.plot(x[done], sdi0[done], "o--", mfc="white", color="0.4", label="SDI, undamaged reference (the method's floor)")
        if (~done).any():
            missing = ", ".join(f"{r['age_days']:g} d" for r, d in zip(rows, done) if not d)
            bx.plot([], [], " ", label=f"SDT not done at {missing}")
        for xi, yi, r in zip(x[done], sdi[done], [r for r, d in zip(rows, done) if d]):
            bx.annotate(f"{r['age_days']:g} d", (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=7, color="0.35")
        bx.legend(fontsize=7, loc="best")
    bx.set_xlim(ax.get_xlim())  # the same expansions as the left panel, even with one SDT done
    bx.set(xlabel="linear expansion at the test age, mean of the x and y strains [%]",
           ylabel="stiffness damage index SDI [-]", title="stiffness damage test")
    bx.set_ylim(0, 1.3 * np.nanmax([r.get(k, np.nan) for r in rows for k in ("SDI", "SDI0")] + [1e-3]))
    bx.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
