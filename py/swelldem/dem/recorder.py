# SPDX-License-Identifier: GPL-2.0-or-later
"""What a swelling test records after every converged physical step, given to the solver as its
``stepHook`` (a Python callable the engine calls with no arguments after each converged step),
and the ParaView time series (swelldem.dem.vtk_series)."""
import os
import time

import numpy as np

from ..measure import affine_strain
from ..paper import KIND_NAME_OF_ID, KIND_NAMES, STRUCTURE_KIND_IDS
from ..plugin import require
from ..report import write_curves, write_results
from .vtk_series import VtkSeries


def _yade():
    return require("swelldem.dem.recorder")


def _pair(i):
    return (i.id1, i.id2) if i.id1 < i.id2 else (i.id2, i.id1)


def bonded_pairs():
    """The (id1, id2) pairs (id1 < id2) of the real, unbroken interactions of O: the bonded contacts
    at the start of a run, the only ones that can break. Contacts the collider makes during the run
    are born broken (cohesionless, compression only) and are counted apart."""
    yade, _ = _yade()
    return frozenset(_pair(i) for i in yade.Omega().interactions if i.isReal and not i.phys.broken)


def contact_arrays(bonded=None):
    """(kindId, Fn [N], broken, bonded) of every real interaction in O, as numpy arrays; bonded[c]
    is whether the interaction's pair is in `bonded` (bonded_pairs() at the start; None: all)."""
    yade, _ = _yade()
    kind, fn, broken, was_bonded = [], [], [], []
    for i in yade.Omega().interactions:
        if not i.isReal:
            continue
        p = i.phys
        kind.append(p.kindId)
        fn.append(p.Fn)
        broken.append(p.broken)
        was_bonded.append(bonded is None or _pair(i) in bonded)
    return np.array(kind, dtype=int), np.array(fn), np.array(broken, dtype=bool), np.array(was_bonded, dtype=bool)


def broken_contacts(bonded=None):
    """(id1, id2, kindId) of every broken real interaction in O whose pair is in `bonded` (None: all):
    the crack map's input."""
    yade, _ = _yade()
    return [(i.id1, i.id2, i.phys.kindId) for i in yade.Omega().interactions
            if i.isReal and i.phys.broken and (bonded is None or _pair(i) in bonded)]


#: The file next to results.json that holds, for every contact bonded at the start, the step at
#: which it broke (report.load_breaks reads it).
BREAKS_FILE = "contact_breaks.npz"


def tensile_capacity():
    """Per kind name, the tensile capacity f_t A of the real, unbroken interactions of O [kN]:
    {'min', 'median', 'max'} over the kind's contacts, and 'f_t_Pa', the kind's tensileStrength;
    for the paper's kinds whether or not damage is on (with damage off it is the capacity the
    contacts do not have), for a structure's kind (BOND) only when it can break: steel and platen
    contacts never do, and a capacity drawn for them would be one they do not have."""
    yade, _ = _yade()
    cap, f_t = {}, {}
    for i in yade.Omega().interactions:
        if i.isReal and not i.phys.broken:
            k = KIND_NAME_OF_ID.get(i.phys.kindId)
            if k in KIND_NAMES or (k is not None and i.phys.kind.damage):
                cap.setdefault(k, []).append(i.phys.kind.tensileStrength * i.phys.area / 1e3)
                f_t[k] = float(i.phys.kind.tensileStrength)
    return {k: {"min": float(np.min(v)), "median": float(np.median(v)), "max": float(np.max(v)), "f_t_Pa": f_t[k]}
            for k, v in cap.items()}


def reference_positions(assembly):
    """The particles' centres as the assembly made them: (n, 2), or (n, 3) for a 3D box [m]."""
    return np.column_stack([assembly.x, assembly.y] + ([assembly.z] if getattr(assembly, "dim", 2) == 3 else []))


def skeleton_weights(assembly):
    """Weights of the specimen's strain fit (measure.affine_strain): the particle's area (volume in
    3D) up to a constant, 0 for a particle with fewer contacts than dimensions: one held by the
    specimen's sides during packing is loose in a free specimen and does not follow it."""
    dim = getattr(assembly, "dim", 2)
    return np.where(assembly.coordination() >= dim, assembly.r ** dim, 0.0)


def add_structure_kinds(res, pair_kind):
    """Gives the structure kinds (PLATEN, STEEL, BOND) that have bonded contacts at the start
    (pair_kind: the kindId of each) their per-kind series in res['per_kind'] and their count in
    res['n_contacts_by_kind'], after the paper's three, unless res holds them already (a resumed
    run). Returns {kind name: kindId} of the kinds the recorder follows: the paper's three, then
    those structure kinds (none in a scene without structures, whose results are unchanged)."""
    ids = {name: k for k, name in enumerate(KIND_NAMES)}
    per_kind, counts = res.get("per_kind"), res.get("n_contacts_by_kind")
    for name, k in STRUCTURE_KIND_IDS.items():
        n = int(np.sum(pair_kind == k))
        if n == 0:
            continue
        ids[name] = k
        if per_kind is not None:
            per_kind.setdefault(name, {"fn_p05_kN": [], "fn_p95_kN": [], "broken": [], "born_broken": []})
        if counts is not None:
            counts.setdefault(name, n)
    return ids


def facet_segments(assembly, pairs, pair_kind):
    """(m, 2, 2) -> (m, 4): each bonded contact's facet as a segment x1, y1, x2, y2 [m], what a
    crack map draws. A contact of the assembly has its Laguerre facet (assembly.facet_segment_m);
    a structure's contact (a bar's, a platen's) is not in the assembly, and its facet is the
    segment across its normal through its contact point, of its facet length (area / thickness),
    read from O at the start. NaN for a 3D box (the crack maps draw a section)."""
    seg = np.full((len(pairs), 4), np.nan)
    if getattr(assembly, "dim", 2) == 3 or not len(pairs):
        return seg
    index = {(int(i), int(j)): c for c, (i, j) in enumerate(assembly.contacts)}
    yade, _ = _yade()
    O = yade.Omega()
    thickness = float(assembly.thickness_m)
    for c, (i, j) in enumerate(pairs.tolist()):
        a = index.get((i, j)) if pair_kind[c] in (0, 1, 2) else None
        if a is not None:
            seg[c] = assembly.facet_segment_m[a]
            continue
        I = O.interactions[i, j]
        p, n = I.geom.contactPoint, I.geom.normal
        half = 0.5 * I.phys.area / thickness
        seg[c] = (p[0] + half * n[1], p[1] - half * n[0], p[0] - half * n[1], p[1] + half * n[0])
    return seg


class StepRecorder:
    """Per converged physical step, appends to the results dict `res`: time [day], the swelling
    strains (affine fit of the skeleton's displacements: x, y and area), the platens' stress [Pa] and
    displacement [m] per axis (0 without platens), the largest and the mean bar stress [Pa] (with bars), the unbalanced-force ratio, the step's
    iterations and round-off flag, and per contact kind (the paper's three, and the structures'
    that the scene has: add_structure_kinds) the 5 % / 95 % normal-force quantiles
    [kN], the broken contacts (bonded at the start, broken since) and the contacts made during
    the run (born broken, 'born_broken', present at the step), under 'per_kind'; sets the
    solver's iterations so far ('iterations', split into 'newton_iterations' and
    'relaxation_iterations'), 'unbalanced_history' (the solver's records of the unbalanced-force
    ratio every historyEvery iterations: 'iteration', cumulative [-], and 'ratio' [-]) and, once, 'tensile_capacity_kN' (tensile_capacity()); then
    rewrites results.json, the curves (report.write_curves: curves.csv, plot_data.txt) and BREAKS_FILE (the step index into times_days at which each bonded
    contact broke, -1 while intact) in `out` (a run that stops later keeps what it had) and, every
    vtk_every steps (0: none), the step's VTK files into out/vtk/ (swelldem.dem.vtk_series; the
    step number in the file names is the index into times_days). Made before the run starts: it
    takes the bonded contacts from O then, and replaces the VTK series of an earlier run in out/vtk/
    (resuming=True: not yet, resume() does it after the state's load). save_state: after the files of
    a step, O.save of the scene to out/STATE_FILE (save_scene), from which scenario.run resumes."""

    def __init__(self, assembly, yscene, solver, res, out, vtk_every=0, platens=None, bars=None, save_state=False, resuming=False):
        self.a, self.ys, self.solver, self.res, self.out, self.vtk_every = assembly, yscene, solver, res, out, vtk_every
        self.platens, self.bars, self.save_state = platens, bars, save_state
        self.particle_fields = None  # further per-particle VTK arrays: a callable of the body ids (VtkSeries.export)
        self.dim = getattr(assembly, "dim", 2)
        self.ref = reference_positions(assembly)
        self.weights = skeleton_weights(assembly)
        self.t0 = time.time()
        self.bonded = bonded_pairs()
        self.vtk = None if resuming else self._vtk_series()
        self.pairs = np.array(sorted(self.bonded), dtype=np.int32).reshape(-1, 2)
        self.pair_index = {tuple(p): c for c, p in enumerate(self.pairs.tolist())}
        self.pair_kind = np.full(len(self.pairs), -1, dtype=np.int8)
        yade, _ = _yade()
        for i in yade.Omega().interactions:
            c = self.pair_index.get(_pair(i)) if i.isReal else None
            if c is not None:
                self.pair_kind[c] = i.phys.kindId
        self.break_step = np.full(len(self.pairs), -1, dtype=np.int32)
        self.segments = facet_segments(assembly, self.pairs, self.pair_kind)
        self.kind_ids = add_structure_kinds(res, self.pair_kind)
        res["tensile_capacity_kN"] = tensile_capacity()

    def _vtk_series(self, keep_before=0):
        if self.dim == 3:
            return VtkSeries(os.path.join(self.out, "vtk"), self.bonded, keep_before=keep_before, cell_volume=self.a.cell_volume_m3)
        return VtkSeries(os.path.join(self.out, "vtk"), self.bonded, cell_area=self.a.cell_area_m2, thickness=self.a.thickness_m,
                         keep_before=keep_before)

    def resume(self, solver):
        """Goes on from a saved state just loaded into O, whose `solver` has done its first k
        converged steps (its stepIterations): the results of `res` (the run's results.json) and
        BREAKS_FILE are cut to those k steps (a run stopped between writing them and saving its
        state recorded one step more), the VTK files of later steps removed, the bars' yield day
        kept only if reached by then. Made with resuming=True on the freshly built scene before the
        load, the recorder holds the bonded contacts, their kinds and the tensile capacity of the
        run's start, as the interrupted run did. Returns k."""
        from ..report import truncate_steps
        self.solver = solver
        k = len(solver.stepIterations)
        r = self.res
        truncate_steps(r, k)
        saved = np.load(os.path.join(self.out, BREAKS_FILE))
        if not np.array_equal(saved["pairs"], self.pairs):
            raise RuntimeError(f"swelldem: {os.path.join(self.out, BREAKS_FILE)} lists other bonded contacts than the rebuilt scene's")
        self.break_step = np.where(saved["break_step"] < k, saved["break_step"], -1).astype(np.int32)
        if self.bars is not None:
            day = r["rebar"]["yield_day"]
            self.bars.yield_day = day if day is not None and k and day <= r["times_days"][-1] else None
            r["rebar"]["yield_day"] = self.bars.yield_day
        self.solver_totals()
        self.vtk = self._vtk_series(keep_before=k)
        self.t0 = time.time() - float(r.get("wall_s") or 0.0)
        return k

    def __call__(self):
        s = affine_strain(self.ref, self.ys.positions(), weights=self.weights)
        kind, fn, broken, bonded = contact_arrays(self.bonded)
        r, solver = self.res, self.solver
        r["times_days"].append(solver.physTime)
        r["swelling_strain_x"].append(s["eps_xx"])
        r["swelling_strain_y"].append(s["eps_yy"])
        # the area (3D: volume) change of the affine fit, det(I + grad u) - 1 (exact, not the
        # small-strain trace)
        change = float(np.linalg.det(np.eye(self.dim) + np.asarray(s["gradient"]))) - 1
        if self.dim == 3:
            r["swelling_strain_z"].append(s["eps_zz"])
            r["swelling_strain_volume"].append(change)
        else:
            r["swelling_strain_area"].append(change)
        for axis in ("x", "y", "z"):
            if f"platen_stress_{axis}_Pa" not in r:  # z: a 3D box's only
                continue
            r[f"platen_stress_{axis}_Pa"].append(self.platens.stress(axis) if self.platens else 0.0)
            r[f"platen_disp_{axis}_m"].append(self.platens.displacement(axis) if self.platens else 0.0)
        if self.bars is not None:
            smax, smean = self.bars.record(solver.physTime)
            r["rebar_stress_max_Pa"].append(smax)
            r["rebar_stress_mean_Pa"].append(smean)
            r["rebar"]["yield_day"] = self.bars.yield_day
        r["unbalanced_ratio"].append(solver.unbalanced)
        r["iterations_per_step"].append(int(solver.stepIterations[-1]))
        round_off = getattr(solver, "stepRoundOff", None)  # a solver without a round-off stop has none
        r["step_at_round_off"].append(bool(round_off[-1]) if round_off else False)
        limit = getattr(solver, "stepRoundOffRatio", None)
        r.setdefault("round_off_ratio", []).append(float(limit[-1]) if limit else float("nan"))
        for name, k in self.kind_ids.items():
            sel = kind == k
            q05, q95 = (np.quantile(fn[sel], [0.05, 0.95]) / 1e3).tolist() if sel.any() else (float("nan"),) * 2
            r["per_kind"][name]["fn_p05_kN"].append(q05)
            r["per_kind"][name]["fn_p95_kN"].append(q95)
            r["per_kind"][name]["broken"].append(int((broken & bonded)[sel].sum()))
            r["per_kind"][name].setdefault("born_broken", []).append(int((~bonded)[sel].sum()))
        self.solver_totals()
        self.mark_breaks(len(r["times_days"]) - 1)
        r["wall_s"] = time.time() - self.t0
        r["updated"] = time.time()  # [s since the epoch] of the last step written: a killed run stays "running"
        if self.vtk_every and len(r["times_days"]) % self.vtk_every == 0:
            self.export_vtk()
        write_results(self.out, r)
        write_curves(self.out, r)
        self.write_breaks()
        if self.save_state:
            save_scene(os.path.join(self.out, STATE_FILE))

    def solver_totals(self):
        """The run's figures the solver holds for all its steps so far: iterations (Newton and
        relaxation), the fallback steps, the step count and the unbalanced-force history."""
        r, solver = self.res, self.solver
        r["iterations"] = solver.totalIterations
        # An iteration of the implicit solver is a Newton iteration or one of dynamic relaxation (its
        # relaxation phases and fallback), which it counts apart; every ADR iteration is one of
        # dynamic relaxation, and the ADR has no such count.
        relaxation = getattr(solver, "relaxationIterations", None)
        r["relaxation_iterations"] = int(solver.totalIterations if relaxation is None else relaxation)
        r["newton_iterations"] = int(solver.totalIterations) - r["relaxation_iterations"]
        r["fallback_steps"] = fallback_steps(solver)
        if hasattr(solver, "factorizations"):
            # the linear solver the run used (linearSolver auto resolved) and the direct solve's cost:
            # numeric factorizations (GAMG: preconditioner set-ups), symbolic analyses, their time and
            # the factor's entries (its fill-in, what sets the memory of a large 3D specimen)
            r["linear_solver"] = {"name": str(solver.linearSolverUsed), "factorizations": int(solver.factorizations), "analyses": int(solver.analyses),
                                  "factor_wall_s": float(solver.factorSeconds), "factor_nonzeros": float(solver.factorNonZeros)}
        r["n_steps"] = int(solver.nSteps)  # the run's physical steps, done or not: a run that stopped has fewer times_days
        r["unbalanced_history"] = {"every": int(getattr(solver, "historyEvery", 0)),
                                   "iteration": [int(v) for v in getattr(solver, "historyIteration", [])],
                                   "ratio": list(getattr(solver, "historyUnbalanced", []))}

    def mark_breaks(self, step):
        """Gives the bonded contacts broken since the last step the index `step`."""
        for i1, i2, _ in broken_contacts(self.bonded):
            c = self.pair_index[(min(i1, i2), max(i1, i2))]
            if self.break_step[c] < 0:
                self.break_step[c] = step

    def write_breaks(self):
        """BREAKS_FILE in out: 'pairs' (m, 2) body ids id1 < id2 of the contacts bonded at the
        start, 'kind' their kindId, 'break_step' the index into times_days of the step at which
        each broke (-1: intact), 'times_days' [day], 'segment_m' (m, 4) each contact's facet as a
        segment x1, y1, x2, y2 at the start [m] (facet_segments; NaN for a 3D box); written to a
        temporary file, then renamed."""
        tmp = os.path.join(self.out, BREAKS_FILE + ".tmp")
        with open(tmp, "wb") as f:
            np.savez_compressed(f, pairs=self.pairs, kind=self.pair_kind, break_step=self.break_step,
                                times_days=np.array(self.res["times_days"], dtype=float), segment_m=self.segments)
        os.replace(tmp, os.path.join(self.out, BREAKS_FILE))

    def export_vtk(self):
        """The VTK files of the last recorded step, unless already written (the run's end exports
        its last step whatever vtk_every)."""
        step = len(self.res["times_days"]) - 1
        if step >= 0 and not self.vtk.exported(step):
            self.vtk.export(step, self.res["times_days"][step], self.particle_fields)


#: With save_state, the scene after the last converged step, from which a run goes on (scenario.run's
#: resume), and the scene at the end of a run. The state is O.save's binary form without gzip, saved
#: at every step: 3 times faster than .yade.gz (30 mm main job: 0.07 s and 2.5 MB against 0.2 s and
#: 1.4 MB); the final scene, saved once, is compressed.
STATE_FILE, FINAL_FILE = "state.yade", "final.yade.gz"


def save_scene(path):
    """O.save to `path` through a temporary file renamed over it: a run stopped during the save
    leaves the previous state whole. The temporary name keeps the extension, which sets O.save's form."""
    yade, _ = _yade()
    folder, name = os.path.split(path)
    tmp = os.path.join(folder, "tmp-" + name)
    yade.Omega().save(tmp, True)
    os.replace(tmp, path)


def fallback_steps(solver):
    """The steps the implicit solver handed to dynamic relaxation (ImplicitLogTimeSolver
    .fallbackIterations), one dict each: step (1..n), t_days [day], why, ratio_at_handover [-],
    changing_contacts [-] (state changes in the last Newton iteration), relaxation_iterations [-]
    and wall_s [s] (the whole step); [] for a solver without a fallback (the ADR)."""
    steps = list(getattr(solver, "fallbackSteps", []))
    out = []
    for i, step in enumerate(steps):
        ratio, changing = solver.fallbackRatio[i], int(solver.fallbackChanging[i])
        out.append({"step": int(step), "t_days": float(solver.times[step]),
                    "why": (f"Newton had not reached the tolerance {solver.tolerance:g} after {solver.fallbackIterations} iterations "
                            f"of a round (ratio {ratio:.2e}, {changing} contacts changing state); dynamic relaxation finished the "
                            f"step at {max(solver.tolerance, solver.fallbackTolerance):g}"),
                    "ratio_at_handover": float(ratio), "changing_contacts": changing,
                    "relaxation_iterations": int(solver.fallbackRelaxation[i]), "wall_s": float(solver.fallbackWall[i])})
    return out


def export_vtk(out, step, time_days, bonded=None, assembly=None):
    """One snapshot of O as a ParaView series of one step in out/vtk/ (see
    swelldem.dem.vtk_series; it replaces an earlier series there). step [-], time_days [day]:
    the step's index and physical time; bonded: see contact_arrays; assembly: the scene's
    mesostructure, whose cell areas and thickness give the discs' stress (None: vtk_series'
    stand-in). Returns the VtkSeries."""
    cells = {} if assembly is None else {"cell_area": assembly.cell_area_m2, "thickness": assembly.thickness_m}
    series = VtkSeries(os.path.join(out, "vtk"), bonded, **cells)
    series.export(step, time_days)
    return series


def standard_outputs(out, assembly, yscene, solver, name="own scene", vtk_every=0):
    """Gives a scene of one's own (built with swelldem.dem.to_yade, before its run) the outputs of
    scripts/swelling_test.py in the folder `out` (made if missing): after every converged step
    results.json, curves.csv, plot_data.txt and contact_breaks.npz (StepRecorder), the ParaView
    files every vtk_every steps (0: the last step only) into out/vtk/; after the last step also
    table.md / table.csv, swelling_strain.png (with the free swelling of the scene's swelling
    kind: swellDispInf / (2 R_mean) times Larive's xi at its tauC, tauL), unbalanced.png,
    force_quantiles.png, crack_map.png and, with damage, crack_map_<day>d.png at the swelling
    kind's tau_L and 2 tau_L; assembly.npz at once. name: the run's name in titles and tables
    (results.json 'scenario'). Call it after setting solver.stepHook to one's own recording, if
    any: it becomes the solver's stepHook and calls that one after its own. Returns the
    StepRecorder; its `res` is the results dict."""
    from ..paper import KIND_NAMES as _names
    from ..report import write_all
    from .scene import functor_kinds, kind_settings, solver_settings
    yade, _ = _yade()
    os.makedirs(out, exist_ok=True)
    assembly.save(os.path.join(out, "assembly.npz"))
    kinds = functor_kinds(yscene.ip2)
    settings = {n: kind_settings(k) for n, k in kinds.items()}
    behaviours = {v["behaviour"] for n, v in settings.items() if n in ("MORTAR", "ITZ")} or {"elastic"}
    res = {"scenario": name, "behaviour": "viscoelastic" if "viscoelastic" in behaviours else sorted(behaviours)[0],
           "damage": any(v.get("damage") for v in settings.values()), "solver": "implicit" if "Implicit" in type(solver).__name__ else "adr",
           "tolerance": solver.tolerance, "config": {"size_mm": [assembly.width_m * 1e3, assembly.height_m * 1e3]},
           "solver_settings": solver_settings(solver), "kinds": settings, "d_inf_m": None, "r_mean_m": float(assembly.r.mean()),
           "n_particles": int(len(assembly.x)), "n_contacts_by_kind": {n: int((assembly.kind == k).sum()) for k, n in enumerate(_names)},
           "times_days": [], "swelling_strain_x": [], "swelling_strain_y": [], "swelling_strain_area": [],
           "platen_stress_x_Pa": [], "platen_stress_y_Pa": [], "platen_disp_x_m": [], "platen_disp_y_m": [], "unbalanced_ratio": [],
           "iterations_per_step": [], "step_at_round_off": [], "round_off_ratio": [], "iterations": 0, "newton_iterations": 0,
           "relaxation_iterations": 0, "per_kind": {n: {"fn_p05_kN": [], "fn_p95_kN": [], "broken": [], "born_broken": []} for n in _names},
           "temperature": {"source": "the kinds' own", "per_kind": {n: {"days": list(k.temperatureDays), "temperatures_K": list(k.temperatures)}
                                                                    for n, k in kinds.items()}},
           "status": "running", "wall_s": 0.0}
    swelling = [v for v in settings.values() if v.get("swelling") and (v.get("swellDispInf") or 0) > 0]
    res["d_inf_m"] = float(swelling[0]["swellDispInf"]) if swelling else 0.0
    rec = StepRecorder(assembly, yscene, solver, res, out, vtk_every=vtk_every)
    own = solver.stepHook

    def hook():
        rec()
        if len(res["times_days"]) >= int(solver.nSteps):  # the last step: the run's figures and tables
            res["status"] = "finished"
            rec.export_vtk()
            write_results(out, res)
            write_all(out, res, assembly, broken_contacts(rec.bonded))
        if own is not None:
            own()

    solver.stepHook = hook
    return rec
