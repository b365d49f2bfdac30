# SPDX-License-Identifier: GPL-2.0-or-later
"""The paper's numerical swelling tests on a generated concrete specimen (ISR, ASR-fine, ASR-coarse),
with elastic (modulus developing with age) or aging viscoelastic contacts, with or without damage.

Run inside YADE with the plugin (scripts/swelling_test.py is the command-line face):

    from swelldem import scenario
    res = scenario.run(scenario.SwellingTest(scenario="isr", behaviour="viscoelastic", damage=True,
                                             size_mm=(30, 30), out="out/isr"))

Decisions (docs/scenarios.md explains them):
- the paper's Table 3.3 q's are its micro (contact) parameters q_i*, and they are used as such by
  default (parameters="paper-micro"); parameters="macro" reads them as macroscopic values and
  derives the contact values through the factor beta measured on a random mortar assembly of the
  same packing (calibrate_modulus_factor: contacts of modulus E_c give a macroscopic modulus
  beta E_c, so E_c = E / beta and each micro q_i = beta q_i, the law being linear in the
  compliance). beta is measured and reported in both cases (the macroscopic moduli it implies);
- 'elastic' runs use aging-elastic mortar and ITZ contacts, E(t) = 1/J(t + 0.01 d, t) of the same
  B3 q's (the paper: "included the development over time of mortar and ITZ modulus");
  aggregate contacts are linear elastic (modulus AGGREGATE_YOUNG, an assumption: the paper gives none);
- the specimen is free (no support); strains are the least-squares affine fit of all displacements.
"""
import json
import os
import time
from dataclasses import asdict, dataclass, field

import numpy as np

KIND_NAMES = ("MORTAR", "ITZ", "AGG")
# Paper Table 3.5: tensile strengths [Pa].
TENSILE_STRENGTH = {"MORTAR": 4e6, "ITZ": 2e6, "AGG": 6e6}
# Paper Table 3.3 materials of each contact kind.
B3_OF_KIND = {"MORTAR": "mortar", "ITZ": "itz"}
AGGREGATE_YOUNG = 60e9  # [Pa] a sound siliceous/calcareous aggregate; not given by the paper
SCENARIOS = {
    "isr": {"kinetics": "isr", "swelling_kinds": ("MORTAR", "ITZ")},
    "asr-fine": {"kinetics": "asr", "swelling_kinds": ("MORTAR",)},
    "asr-coarse": {"kinetics": "asr", "swelling_kinds": ()},  # a fraction of AGG contacts: gel pockets
}
BEHAVIOURS = ("elastic", "viscoelastic")


def _bad(name, value, allowed):
    raise ValueError(f"swelldem: {name} = {value!r} is out of range; allowed: {allowed}")


@dataclass
class SwellingTest:
    """One swelling test. Lengths in mm where the name says so, times in days."""
    scenario: str = "isr"                 # isr | asr-fine | asr-coarse
    behaviour: str = "viscoelastic"       # elastic (aging modulus) | viscoelastic (aging, B3)
    damage: bool = True                   # brittle contacts (paper Table 3.5 strengths)
    size_mm: tuple = (30.0, 30.0)         # specimen width, height [mm]
    seed: int = 1                         # mesostructure seed
    steps_per_decade: float = 10          # physical steps per decade of log time
    tolerance: float = 1e-4               # ADR unbalanced-force ratio
    t_start_days: float = 1.0             # age of the stress-free start [day]
    t_end_days: float = 0.0               # 0: the paper's (3650 d ISR, 50000 d ASR)
    eps_inf: float = 1000e-6              # ultimate free swelling strain of the swelling material [-]
    gel_fraction: float = 0.1             # asr-coarse: share of AGG contacts that swell [-]
    shear_ratio: float = 0.3              # ks / kn of every contact [-]
    aggregate_young: float = AGGREGATE_YOUNG  # contact modulus of aggregate contacts (paper-micro) [Pa]
    strength_scale: float = 1.0           # factor on the paper's tensile strengths [-]
    kelvin_units_per_decade: float = 1.0  # Kelvin chain density [1/decade]
    parameters: str = "paper-micro"       # paper-micro: Table 3.3 q's and AGGREGATE_YOUNG are contact values; macro: scaled by beta
    aggregate_area_fraction: float = -1   # < 0: the generator's default
    vtk_every: int = 0                    # VTK every k physical steps (0: only the last)
    out: str = "out/swelling"
    extra: dict = field(default_factory=dict)

    def validate(self):
        if self.scenario not in SCENARIOS:
            _bad("scenario", self.scenario, ", ".join(SCENARIOS))
        if self.behaviour not in BEHAVIOURS:
            _bad("behaviour", self.behaviour, ", ".join(BEHAVIOURS))
        if len(self.size_mm) != 2 or min(self.size_mm) <= 0:
            _bad("size_mm", self.size_mm, "two positive lengths [mm]")
        if not self.steps_per_decade > 0:
            _bad("steps_per_decade", self.steps_per_decade, "> 0")
        if not 0 < self.tolerance < 1:
            _bad("tolerance", self.tolerance, "0 < tolerance < 1")
        if not self.t_start_days > 0:
            _bad("t_start_days", self.t_start_days, "> 0 [day]")
        if self.t_end_days and self.t_end_days <= self.t_start_days:
            _bad("t_end_days", self.t_end_days, f"> t_start_days = {self.t_start_days} (or 0 for the paper's)")
        if not self.eps_inf >= 0:
            _bad("eps_inf", self.eps_inf, ">= 0")
        if not 0 <= self.gel_fraction <= 1:
            _bad("gel_fraction", self.gel_fraction, "0 <= gel_fraction <= 1")
        if not self.shear_ratio > 0:
            _bad("shear_ratio", self.shear_ratio, "> 0")
        if not self.aggregate_young > 0:
            _bad("aggregate_young", self.aggregate_young, "> 0 [Pa]")
        if not self.strength_scale > 0:
            _bad("strength_scale", self.strength_scale, "> 0")
        if self.parameters not in ("paper-micro", "macro"):
            _bad("parameters", self.parameters, "paper-micro, macro")
        if self.vtk_every < 0:
            _bad("vtk_every", self.vtk_every, ">= 0")

    @property
    def t_end(self):
        from .scene import KINETICS
        return self.t_end_days or KINETICS[SCENARIOS[self.scenario]["kinetics"]][2]


def _yade():
    from .plugin import require
    return require("swelldem.scenario")


def calibrate_modulus_factor(shear_ratio=0.3, seed=11, size_mm=15.0, strain=1e-4, **meso_overrides):
    """beta = E_macro / E_c of a random mortar assembly (no aggregates) whose contacts have modulus
    E_c and shear ratio `shear_ratio`, from a uniaxial tension test solved with the ADR solver:
    the left band held in x, the right band moved by strain x width, y free but for one disc."""
    yade, W = _yade()
    from . import meso, scene
    a = meso.generate(seed=seed, width_mm=size_mm, height_mm=size_mm, aggregate_area_fraction=0, **meso_overrides)
    e_c = 1e9
    kind = scene.contact_kind("MORTAR", behaviour="elastic", young=e_c, shear_ratio=shear_ratio)
    solver = W.AdrLogTimeIntegrator(tStart=1.0, tEnd=10.0, stepsPerDecade=1, tolerance=1e-6, verbose=False)
    meso.to_yade(a, {"MORTAR": kind}, solver)
    O = yade.Omega()
    band = 1.5 * a.r.max()
    left = np.flatnonzero(a.x - a.r < band)
    right = np.flatnonzero(a.x + a.r > a.width_m - band)
    delta = strain * a.width_m
    for i in left:
        O.bodies[int(i)].state.blockedDOFs = "xzXY"
    bottom = int(left[np.argmin(a.y[left])])
    O.bodies[bottom].state.blockedDOFs = "xyzXY"
    for i in right:
        b = O.bodies[int(i)]
        b.state.blockedDOFs = "xzXY"
        b.state.pos = b.state.pos + yade.Vector3(delta, 0, 0)
    scene.run_to_end(solver)
    reaction = -sum(O.forces.f(int(i))[0] for i in right)
    sigma = reaction / (a.height_m * a.thickness_m)
    beta = sigma / strain / e_c
    return {"beta": beta, "e_macro_per_e_c": beta, "n_particles": len(a.x), "size_mm": size_mm, "seed": seed,
            "shear_ratio": shear_ratio, "strain": strain, "adr_iterations": solver.totalIterations}


def make_kinds(test, beta, d_inf):
    """The three ContactKind objects of a test (micro parameters from the macro ones through beta)."""
    from .scene import contact_kind
    sc = SCENARIOS[test.scenario]
    kinds = {}
    for name in KIND_NAMES:
        swells = name in sc["swelling_kinds"] or (test.scenario == "asr-coarse" and name == "AGG")
        common = dict(shear_ratio=test.shear_ratio, kinetics=sc["kinetics"], damage=test.damage,
                      tensile_strength=TENSILE_STRENGTH[name] * test.strength_scale, swelling=swells,
                      swell_disp_inf=d_inf if name in sc["swelling_kinds"] else 0.0)
        if name == "AGG":
            k = contact_kind(name, behaviour="elastic", young=test.aggregate_young / beta, **common)
        else:
            behaviour = "viscoelastic" if test.behaviour == "viscoelastic" else "aging-elastic"
            k = contact_kind(name, behaviour=behaviour, b3=B3_OF_KIND[name], **common)
            k.q1, k.q2, k.q3, k.q4 = (beta * q for q in (k.q1, k.q2, k.q3, k.q4))
            k.kelvinUnitsPerDecade = test.kelvin_units_per_decade
        kinds[name] = k
    return kinds


class _Recorder:
    """Per converged physical step: strains, force quantiles and broken contacts per kind."""

    def __init__(self, test, assembly, yscene, solver, res, out):
        self.test, self.a, self.ys, self.solver, self.res, self.out = test, assembly, yscene, solver, res, out
        self.ref = np.column_stack([assembly.x, assembly.y])
        # Strain of the load-bearing skeleton: discs with fewer than 2 contacts (held by the
        # specimen's sides during packing) are loose in a free specimen and do not follow it.
        self.weights = np.where(assembly.coordination() >= 2, assembly.r ** 2, 0.0)
        self.t0 = time.time()

    def contact_arrays(self):
        yade, _ = _yade()
        O = yade.Omega()
        kind, fn, broken = [], [], []
        for i in O.interactions:
            if not i.isReal:
                continue
            p = i.phys
            kind.append(p.kindId)
            fn.append(p.Fn)
            broken.append(p.broken)
        return np.array(kind, dtype=int), np.array(fn), np.array(broken, dtype=bool)

    def __call__(self):
        from .measure import affine_strain
        yade, _ = _yade()
        O = yade.Omega()
        cur = np.array([[O.bodies[int(i)].state.pos[0], O.bodies[int(i)].state.pos[1]] for i in self.ys.ids])
        s = affine_strain(self.ref, cur, weights=self.weights)
        kind, fn, broken = self.contact_arrays()
        r = self.res
        r["times_days"].append(self.solver.physTime)
        r["swelling_strain_x"].append(s["eps_xx"])
        r["swelling_strain_y"].append(s["eps_yy"])
        r["unbalanced_ratio"].append(self.solver.unbalanced)
        r["adr_iterations_per_step"].append(int(self.solver.stepIterations[-1]))
        r["step_at_round_off"].append(bool(self.solver.stepRoundOff[-1]))
        for k, name in enumerate(KIND_NAMES):
            sel = kind == k
            q05, q95 = (np.quantile(fn[sel], [0.05, 0.95]) / 1e3).tolist() if sel.any() else (float("nan"),) * 2
            r["per_kind"][name]["fn_p05_kN"].append(q05)
            r["per_kind"][name]["fn_p95_kN"].append(q95)
            r["per_kind"][name]["broken"].append(int(broken[sel].sum()))
        r["adr_iterations"] = self.solver.totalIterations
        r["wall_s"] = time.time() - self.t0
        if self.test.vtk_every and self.solver.step % self.test.vtk_every == 0:
            export_vtk(self.out, self.a)
        write_json(self.out, r)  # a run that stops later keeps what it had


def write_json(out, res):
    flat = dict(res)
    for name, d in res["per_kind"].items():  # the contract's flat keys as well
        for key, v in d.items():
            flat[f"{key}_{name}"] = v
    with open(os.path.join(out, "results.json.tmp"), "w") as f:
        json.dump(flat, f, indent=1, default=float)
    os.replace(os.path.join(out, "results.json.tmp"), os.path.join(out, "results.json"))


def export_vtk(out, assembly):
    """Particles and contacts through YADE's own exporter (ParaView opens the .vtu/.vtk files)."""
    yade, _ = _yade()
    from yade import export
    os.makedirs(os.path.join(out, "vtk"), exist_ok=True)
    vtk = export.VTKExporter(os.path.join(out, "vtk", "swelling"))
    vtk.exportSpheres(what=dict(aggregateId="b.material.aggregateId", displacement="b.state.displ()"))
    vtk.exportInteractions(what=dict(kind="i.phys.kindId", fn="i.phys.Fn", broken="float(i.phys.broken)"))


def run(test):
    """Runs one swelling test inside YADE; writes results.json, tables, plots and VTK into test.out."""
    test.validate()
    yade, W = _yade()
    from . import meso, report
    t0 = time.time()
    os.makedirs(test.out, exist_ok=True)
    overrides = {} if test.aggregate_area_fraction < 0 else {"aggregate_area_fraction": test.aggregate_area_fraction}
    assembly = meso.generate(seed=test.seed, width_mm=test.size_mm[0], height_mm=test.size_mm[1], **overrides)
    assembly.save(os.path.join(test.out, "assembly.npz"))
    cal = calibrate_modulus_factor(shear_ratio=test.shear_ratio)
    r_mean = float(assembly.r.mean())
    d_inf = test.eps_inf * 2 * r_mean  # the paper's micro-macro rule (Table 3.2)
    scale = cal["beta"] if test.parameters == "macro" else 1.0
    kinds = make_kinds(test, scale, d_inf)
    cal["macro_young_28d_Pa"] = {name: cal["beta"] / (scale * kinds[name].compliance(28.01, 28.0)) for name in ("MORTAR", "ITZ")}
    cal["macro_young_28d_Pa"]["AGG"] = cal["beta"] * kinds["AGG"].young
    solver = W.AdrLogTimeIntegrator(tStart=test.t_start_days, tEnd=test.t_end, stepsPerDecade=test.steps_per_decade,
                                    tolerance=test.tolerance, label="swelldemSolver")
    ys = meso.to_yade(assembly, kinds, solver)
    gel = []
    if test.scenario == "asr-coarse":
        gel = meso.set_gel_pockets(ys, assembly, test.gel_fraction, d_inf, test.seed)
    counts = {name: int((assembly.kind == k).sum()) for k, name in enumerate(KIND_NAMES)}
    res = {"scenario": test.scenario, "behaviour": test.behaviour, "damage": test.damage, "config": asdict(test),
           "calibration": cal, "d_inf_m": d_inf, "r_mean_m": r_mean, "n_particles": int(len(assembly.x)),
           "n_contacts_by_kind": counts, "n_gel_pockets": int(len(gel)), "times_days": [], "swelling_strain_x": [],
           "swelling_strain_y": [], "unbalanced_ratio": [], "adr_iterations_per_step": [], "step_at_round_off": [], "adr_iterations": 0,
           "per_kind": {n: {"fn_p05_kN": [], "fn_p95_kN": [], "broken": []} for n in KIND_NAMES},
           "status": "running", "wall_s": 0.0}
    rec = _Recorder(test, assembly, ys, solver, res, test.out)
    solver.stepHook = rec
    try:
        from .scene import run_to_end
        run_to_end(solver)
        res["status"] = "finished"
    except Exception as e:  # noqa: BLE001 - the message goes into the results, then up
        res["status"] = f"failed: {e}"
        write_json(test.out, res)
        raise
    finally:
        res["wall_s"] = time.time() - t0
    export_vtk(test.out, assembly)
    write_json(test.out, res)
    report.write_all(test.out, res, assembly, rec.contact_arrays, yade.Omega())
    return res
