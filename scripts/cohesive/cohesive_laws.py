# SPDX-License-Identifier: GPL-2.0-or-later
"""The same concrete mesostructure under YADE's stock cohesive laws and under swelldem's law
(issue 8): quasi-static uniaxial tension and compression, identical loading for every law.

Laws (``LAWS``):

* ``swelldem``: Law2_ScGeom_SwellPhys_AgingSwelling, 'elastic' kinds, damage on (paper Table 3.5
  strengths), creep and swelling off: elastic-brittle, kn = E_c A / L, ks = 0.3 kn;
* ``cohfrict``: Law2_ScGeom6D_CohFrictPhys_CohesionMoment (CohFrictMat/CohFrictPhys), every bonded
  contact given our kn, ks, normalAdhesion = f_t A, a shear adhesion that never binds (our intact
  contacts have no shear limit), the stress-free overlap (unp), no moments (momentRotationLaw off),
  neverErase (a broken bond stays as a frictional, compression-only contact, as ours);
* ``jcfpm``: Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM, the same per-contact kn, ks,
  FnMax = f_t A, FsMax that never binds, crossSection = A, neverErase;
* ``cpm``: Law2_ScGeom_CpmPhys_Cpm (YADE's concrete model); per-contact values from its own Ip2
  (cross-section pi r_min^2, kn = E A/L, ks = poisson kn) and one material, whose ``young`` and
  ``epsCrackOnset`` are calibrated so that the specimen's macroscopic modulus and tensile peak
  equal those of the swelldem run (:func:`calibrate_cpm`).

Loading (:func:`run_uniaxial`): the library's virtual uniaxial test (swelldem.dem.uniaxial),
displacement-controlled between two bands of discs, NewtonIntegrator with local damping.

A study module beside its command-line face, compare_cohesive_laws.py (run inside YADE with the
plugin, scripts/yade-swelldem); docs/cohesive-laws.md reports the runs.
"""
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "py"))
from swelldem import dem, measure, meso, options  # noqa: E402
from swelldem.dem import uniaxial  # noqa: E402
from swelldem.dem.uniaxial import count_per_kind, fit_modulus, stable_dt  # noqa: E402
from swelldem.paper import AGGREGATE_YOUNG, KIND_NAMES, TENSILE_STRENGTH, larive_xi  # noqa: E402
from swelldem.plugin import require  # noqa: E402

LAWS = ("swelldem", "cohfrict", "jcfpm", "cpm")
#: Age [day] at which the macroscopic moduli of mortar and ITZ are taken (E = 1/J(t + 0.01, t)).
AGE_DAYS = 28.0
SHEAR_RATIO = 0.3           # ks / kn, as scenario.SwellingTest
FRICTION_ANGLE = 0.5        # [rad] broken contacts (Coulomb), every law
NEVER = 1e30                # [N] a shear strength that never binds
DENSITY = 2400.0            # [kg/m3]
#: Cpm's own constants that are not calibrated, from the concrete values of YADE's Cpm examples
#: (young 24 GPa, epsCrackOnset 1e-4, sigmaT 3.5 MPa, relDuctility 30). sigmaT is a stress on
#: Cpm's cross-section pi r_min^2, which in a 1 m thick 2D specimen is ~1000 times smaller than
#: the facet area, so `young` must be ~1e14 Pa for the same kn; an absolute 3.5 MPa would then sit
#: far below the contact stresses (young x strain ~ 1e9 Pa) and let every bond slide in shear from
#: the first step (measured: 4 GPa instead of 41). It is therefore kept at the examples' ratio to
#: the tensile stress at crack onset: sigmaT = CPM_SIGMA_T_RATIO x young x epsCrackOnset.
CPM_SIGMA_T_RATIO = 3.5e6 / (24e9 * 1e-4)  # [-]
CPM_REL_DUCTILITY = 30.0    # [-] epsFracture / epsCrackOnset
CPM_OMEGA_BROKEN = 0.99     # a Cpm contact counts as broken when its damage omega exceeds this
LAW_TITLES = {"swelldem": "swelldem (elastic-brittle)", "cohfrict": "CohFrictPhys (matched)",
              "jcfpm": "JCFpmPhys (matched)", "cpm": "CpmPhys (calibrated)"}


def _yade():
    return require("cohesive_laws")


def contact_moduli(beta):
    """Contact moduli E_c [Pa] per kind: macroscopic moduli over beta (as scenario.make_kinds):
    mortar and ITZ E(AGE_DAYS) of the paper's B3 q's, aggregate paper.AGGREGATE_YOUNG."""
    e = {}
    for name, b3 in (("MORTAR", "mortar"), ("ITZ", "itz")):
        e[name] = dem.contact_kind(name, behaviour="aging-elastic", b3=b3).modulus(AGE_DAYS) / beta
    e["AGG"] = AGGREGATE_YOUNG / beta
    return e


def swelldem_kinds(moduli, damage=True, strengths=None):
    strengths = strengths or TENSILE_STRENGTH
    return {name: dem.contact_kind(name, behaviour="elastic", young=moduli[name], shear_ratio=SHEAR_RATIO, damage=damage,
                               tensile_strength=strengths[name], residualFrictionAngle=FRICTION_ANGLE)
            for name in KIND_NAMES}


def build(law, assembly, moduli, damping=0.6, strengths=None, cpm=None, damage=True):
    """Fill O with the assembly under `law` (one of LAWS); returns a dict with the per-contact
    stiffnesses and strengths actually set (kn, ks, fmax arrays in assembly contact order)."""
    yade, W = _yade()
    O = yade.Omega()
    strengths = strengths or TENSILE_STRENGTH
    kinds = swelldem_kinds(moduli, damage=damage, strengths=strengths)
    # Ours first: it defines kn, ks (kn = E_c A / L from the Laguerre facet area A).
    ys = dem.to_yade(assembly, kinds, W.NewtonIntegrator(damping=damping, label="newton"))
    contacts = ys.contacts
    # The law sets kn, ks at each contact's first iteration (facet area known by then): one step at
    # rest with a vanishing dt, then kn = E_c A / L is read back and checked.
    O.dt = 1e-20
    O.step()
    kn = np.array([ys.interaction(c).phys.kn for c in range(len(contacts))])
    ks = np.array([ys.interaction(c).phys.ks for c in range(len(contacts))])
    e_c = np.array([moduli[KIND_NAMES[k]] for k in assembly.kind])
    kn_expected = e_c * assembly.facet_area_m2 / assembly.distance_m
    if np.max(np.abs(kn / kn_expected - 1)) > 1e-9 or np.max(np.abs(ks / (SHEAR_RATIO * kn) - 1)) > 1e-12:
        raise RuntimeError("cohesive_laws: the law's kn differs from E_c A / L")
    ft = np.array([strengths[KIND_NAMES[k]] for k in assembly.kind])
    fmax = ft * assembly.facet_area_m2
    info = {"law": law, "kn": kn, "ks": ks, "fmax": fmax, "contacts": contacts}
    if law == "swelldem":
        return info

    def scene(mat, ig2, ip2, law2):  # the same discs, engines and bonded contacts under a stock law
        return dem.build_scene(assembly.x, assembly.y, assembly.r, [mat], ip2, law2, W.NewtonIntegrator(damping=damping, label="newton"),
                               contacts=contacts, ig2=ig2)[1]

    if law == "cohfrict":
        mat = W.CohFrictMat(young=30e9, poisson=SHEAR_RATIO, density=DENSITY, frictionAngle=FRICTION_ANGLE, isCohesive=True,
                            fragile=True, momentRotationLaw=False, normalCohesion=1.0, shearCohesion=1.0)
        ip2 = W.Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionOnNewContacts=True)
        inters = scene(mat, W.Ig2_Sphere_Sphere_ScGeom6D(), ip2, W.Law2_ScGeom6D_CohFrictPhys_CohesionMoment(neverErase=True))
        for c, I in enumerate(inters):
            p = I.phys
            p.kn, p.ks = float(kn[c]), float(ks[c])
            p.normalAdhesion = float(fmax[c]) if damage else NEVER
            p.shearAdhesion = NEVER
            p.tangensOfFrictionAngle = math.tan(FRICTION_ANGLE)
            p.unp = I.geom.penetrationDepth  # stress-free at the initial distance (gap included)
            p.momentRotationLaw = False
            if p.cohesionBroken:
                raise RuntimeError("cohesive_laws: CohFrictPhys contact created without cohesion")
        ip2.setCohesionOnNewContacts = False  # contacts made later are cohesionless
    elif law == "jcfpm":
        mat = W.JCFpmMat(young=30e9, poisson=SHEAR_RATIO, density=DENSITY, frictionAngle=FRICTION_ANGLE,
                         tensileStrength=4e6, cohesion=4e6, residualFrictionAngle=FRICTION_ANGLE * 180 / math.pi)
        inters = scene(mat, W.Ig2_Sphere_Sphere_ScGeom(), W.Ip2_JCFpmMat_JCFpmMat_JCFpmPhys(cohesiveTresholdIteration=1),
                       W.Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM(neverErase=True, label="jcfLaw"))
        for c, I in enumerate(inters):
            p = I.phys
            if not p.isCohesive:
                raise RuntimeError("cohesive_laws: JCFpmPhys contact created without cohesion")
            p.kn, p.ks = float(kn[c]), float(ks[c])
            p.FnMax = float(fmax[c]) if damage else NEVER
            p.FsMax = NEVER
            p.tanFrictionAngle = math.tan(FRICTION_ANGLE)
            p.crossSection = float(assembly.facet_area_m2[c])
    elif law == "cpm":
        cpm = cpm or {}
        young, eco = cpm.get("young", 30e9), cpm.get("epsCrackOnset", 1e-4)
        mat = W.CpmMat(young=young, poisson=SHEAR_RATIO, density=DENSITY, frictionAngle=FRICTION_ANGLE,
                       sigmaT=cpm.get("sigmaT", CPM_SIGMA_T_RATIO * young * eco), epsCrackOnset=eco,
                       relDuctility=cpm.get("relDuctility", CPM_REL_DUCTILITY), neverDamage=not damage)
        scene(mat, W.Ig2_Sphere_Sphere_ScGeom(), W.Ip2_CpmMat_CpmMat_CpmPhys(cohesiveThresholdIter=10), W.Law2_ScGeom_CpmPhys_Cpm())
        # kn, ks are set by the law at the contact's first step
    else:
        raise ValueError(f"cohesive_laws: law = {law!r} is out of range; allowed: {', '.join(LAWS)}")
    return info


def _is_broken(law, p):
    if law == "swelldem":
        return bool(p.broken)
    if law == "cohfrict":
        return bool(p.cohesionBroken)
    if law == "jcfpm":
        return not p.isCohesive
    return p.omega > CPM_OMEGA_BROKEN


def broken_mask(law, contacts):
    """Per assembly contact: bond broken (an erased interaction counts as broken)."""
    return uniaxial.broken_contacts(contacts, lambda p: _is_broken(law, p))


def damaged_count(law, contacts):
    """Cpm only: contacts with any damage (omega > 0)."""
    yade, _ = _yade()
    O = yade.Omega()
    if law != "cpm":
        return None
    n = 0
    for i, j in contacts:
        if O.interactions.has(int(i), int(j)):
            n += O.interactions[int(i), int(j)].phys.omega > 0
    return int(n)


def run_uniaxial(law, assembly, info, mode="tension", deps_per_step=2e-8, chunk=50, max_strain=None, drop=0.5,
                 safety=0.3, min_strain=0.0):
    """The library's uniaxial test (swelldem.dem.uniaxial.run_uniaxial) of the scene in O built by
    :func:`build` under `law`, with that law's broken bonds (and Cpm's damage), plus per-law counts:
    JCFpm's tensile and shear cracks, swelldem's failure modes of the broken contacts."""
    yade, _ = _yade()
    O = yade.Omega()
    contacts = info["contacts"]
    res = uniaxial.run_uniaxial(assembly, contacts, mode, deps_per_step=deps_per_step, chunk=chunk, max_strain=max_strain,
                                drop=drop, safety=safety, min_strain=min_strain, broken=lambda c: broken_mask(law, c),
                                damaged=(lambda c: damaged_count(law, c)) if law == "cpm" else None)
    res["law"] = law
    if law == "jcfpm":
        lw = O.engines[2].lawDispatcher.functors[0]
        res["jcfpm_tensile_shear_cracks"] = [int(lw.nbTensCracks), int(lw.nbShearCracks)]
    if law == "swelldem":
        modes = {}
        for c in res["broken_contacts_end"]:
            i, j = contacts[c]
            m = int(O.interactions[int(i), int(j)].phys.failureMode)
            modes[m] = modes.get(m, 0) + 1
        res["swelldem_failure_modes"] = {str(k): v for k, v in modes.items()}
    return res


def calibrate_cpm(assembly, moduli, target_modulus, target_peak, deps_per_step, damping, iterations=2, log=print):
    """Cpm's young and epsCrackOnset so that the tension test gives target_modulus and target_peak.
    The macroscopic modulus is proportional to young (linear elasticity). At fixed young, every
    threshold of the law scales with epsCrackOnset (damage is strain-based and sigmaT is tied to
    young x epsCrackOnset), so the peak is proportional to it up to the loading rate; `iterations`
    runs refine it."""
    yade, _ = _yade()
    p = {"young": 30e9, "epsCrackOnset": 1e-4}
    # 1. modulus: an elastic run (neverDamage) to a small strain
    info = build("cpm", assembly, moduli, damping=damping, cpm=p, damage=False)
    # same strain rate as the tests (a faster, shorter run measures the start-up transient, not E)
    r = run_uniaxial("cpm", assembly, info, "tension", deps_per_step=deps_per_step, max_strain=4e-5, drop=0.0)
    e0 = fit_modulus(np.array(r["strain"]), np.array(r["stress_Pa"]), 4e-5, 4e-5)
    p["young"] *= target_modulus / e0
    log(f"cpm calibration: young {p['young']:.4g} Pa (elastic run: E_macro {e0:.4g} Pa per 30 GPa)")
    # 2. tensile peak: epsCrackOnset, scaled by the peak ratio
    eco = target_peak / target_modulus
    history = []
    for it in range(iterations):
        p["epsCrackOnset"] = eco
        info = build("cpm", assembly, moduli, damping=damping, cpm=p)
        r = run_uniaxial("cpm", assembly, info, "tension", deps_per_step=deps_per_step)
        history.append({"epsCrackOnset": eco, "peak_Pa": r["peak_stress_Pa"], "modulus_Pa": r["modulus_Pa"], "wall_s": r["wall_s"]})
        log(f"cpm calibration {it + 1}: epsCrackOnset {eco:.4g} -> peak {r['peak_stress_Pa'] / 1e6:.3f} MPa "
            f"(target {target_peak / 1e6:.3f}), E {r['modulus_Pa'] / 1e9:.2f} GPa")
        eco *= target_peak / r["peak_stress_Pa"]
    p["epsCrackOnset"] = eco
    p["sigmaT"] = CPM_SIGMA_T_RATIO * p["young"] * eco
    p["history"] = history
    p["modulus_per_30GPa"] = e0
    return p



#: Free-swelling comparison: ISR kinetics (paper: tau_c 50 d, tau_L 100 d) from 1 to 3650 days.
SWELL_KINETICS = "isr"
SWELL_T_START, SWELL_T_END = 1.0, 3650.0   # [day]


def larive_fraction(t0, t1, kinetics=SWELL_KINETICS):
    """xi(t1) - xi(t0) of Larive's sigmoid (paper.larive_xi): the swelling our law applies from t0
    to t1, by which the stock laws' radius growth is scaled."""
    return float(larive_xi(t1, kinetics) - larive_xi(t0, kinetics))


def disc_growth(assembly, eps_inf, pattern="mortar"):
    """Per-disc radial swelling strain g_i [-]: 'mortar' (the cement paste swells, aggregates do
    not: g = eps_inf on mortar discs, 0 on aggregate discs, the closest a radius growth comes to
    ISR) or 'uniform' (every disc)."""
    if pattern == "mortar":
        return np.where(np.asarray(assembly.material) == meso.MORTAR_MATERIAL, eps_inf, 0.0)
    if pattern == "uniform":
        return np.full(assembly.n_particles, float(eps_inf))
    raise ValueError(f"cohesive_laws: pattern = {pattern!r} is out of range; allowed: mortar, uniform")


def contact_normal_forces(law, contacts):
    """Normal force per assembly contact, tension positive [N] (0 where no interaction is left)."""
    yade, _ = _yade()
    O = yade.Omega()
    fn = np.zeros(len(contacts))
    for c, (i, j) in enumerate(contacts):
        if not O.interactions.has(int(i), int(j)):
            continue
        I = O.interactions[int(i), int(j)]
        if not I.isReal:
            continue
        if law == "swelldem":
            fn[c] = I.phys.Fn
        else:  # YADE's normalForce acts on body 2 along the normal (from 1 to 2): compression along +n
            fn[c] = -I.phys.normalForce.dot(I.geom.normal)
    return fn


def free_swelling(law, assembly, moduli, eps_inf=1000e-6, pattern="mortar", damage=False, tolerance=1e-6,
                  ramp_steps=4000, max_steps=200000, damping=0.6, steps_per_decade=10, log=None):
    """Free swelling of the unsupported specimen to the end of ISR kinetics.

    swelldem: its own swelling, every contact c = (i, j) with the per-contact ultimate swelling
    displacement d_inf = g_i r_i + g_j r_j (:func:`disc_growth`), ISR kinetics over log time with
    the ADR (tolerance on its unbalanced-force ratio). Stock laws (cohfrict, jcfpm): no swelling
    of their own, so the YADE route: radii grown to r_i (1 + g_i f), f = xi(3650) - xi(1) (the
    same swelling as ours at the end), linearly over `ramp_steps` Newton steps, then relaxed
    until utils.unbalancedForce() < tolerance. Both rest lengths grow by the same amount, so
    without damage the end states are the same equilibrium problem. Returns a dict (SI)."""
    options.number("eps_inf", eps_inf, lo=0, lo_incl=True)
    options.tolerance("tolerance", tolerance)
    options.integer("ramp_steps", ramp_steps, lo=1)
    options.integer("max_steps", max_steps, lo=ramp_steps, allowed=f"an integer >= ramp_steps = {ramp_steps}")
    options.number("damping", damping, lo=0, hi=1, lo_incl=True)
    options.number("steps_per_decade", steps_per_decade, lo=0)
    yade, W = _yade()
    O = yade.Omega()
    t0 = time.time()
    g = disc_growth(assembly, eps_inf, pattern)
    frac = larive_fraction(SWELL_T_START, SWELL_T_END)
    ref = np.column_stack([assembly.x, assembly.y])
    res = {"law": law, "case": f"free swelling ({pattern})", "pattern": pattern, "eps_inf": eps_inf, "xi_fraction": frac,
           "damage": damage, "tolerance": tolerance}
    if law == "swelldem":
        kinds = {name: dem.contact_kind(name, behaviour="elastic", young=moduli[name], shear_ratio=SHEAR_RATIO, damage=damage,
                                    tensile_strength=TENSILE_STRENGTH[name], residualFrictionAngle=FRICTION_ANGLE,
                                    kinetics=SWELL_KINETICS, swelling=True)
                 for name in KIND_NAMES}
        solver = dem.make_solver("adr", tStart=SWELL_T_START, tEnd=SWELL_T_END, stepsPerDecade=steps_per_decade,
                                 tolerance=tolerance, verbose=False)
        ys = dem.to_yade(assembly, kinds, solver)
        contacts = np.asarray(ys.contacts)
        i, j = contacts[:, 0], contacts[:, 1]
        dem.set_contact_swelling(ys, np.arange(len(contacts)), g[i] * assembly.r[i] + g[j] * assembly.r[j])
        dem.run_to_end(solver)
        res.update(steps=int(solver.totalIterations), unbalanced=float(solver.unbalanced))
    elif law in ("cohfrict", "jcfpm"):
        info = build(law, assembly, moduli, damping=damping, damage=damage)
        contacts = info["contacts"]
        O.dt = 1e-20
        O.step()
        O.dt = stable_dt()
        r0 = np.array(assembly.r, dtype=float)
        target = r0 * (1 + g * frac)
        growing = [(O.bodies[int(k)].shape, float(r0[k]), float(target[k] - r0[k])) for k in np.flatnonzero(g)]
        steps = 0
        while steps < ramp_steps:
            steps += 1
            s = steps / ramp_steps
            for shape, r, dr in growing:
                shape.radius = r + s * dr
            O.step()
        unb = yade.utils.unbalancedForce()
        while unb > tolerance and steps < max_steps:
            O.run(500, True)
            steps += 500
            unb = yade.utils.unbalancedForce()
        res.update(steps=steps, unbalanced=float(unb), dt_s=O.dt)
        if unb > tolerance:
            res["status"] = f"not relaxed: unbalancedForce {unb:.3g} after {steps} steps"
    else:
        raise ValueError(f"cohesive_laws: law = {law!r} has no free-swelling case; allowed: swelldem, cohfrict, jcfpm")
    cur = np.array([[O.bodies[k].state.pos[0], O.bodies[k].state.pos[1]] for k in range(assembly.n_particles)])
    sel = assembly.coordination() >= 2  # discs held by fewer than 2 contacts are loose in a free specimen
    st = measure.affine_strain(ref[sel], cur[sel])
    fn = contact_normal_forces(law, contacts)
    br = broken_mask(law, contacts)
    kind = np.asarray(assembly.kind)
    q = {}
    for k, name in enumerate(KIND_NAMES):
        f = fn[kind == k]
        q[name] = [float(np.percentile(f, 5)), float(np.percentile(f, 95))] if len(f) else [float("nan")] * 2
    res.update(eps_xx=st["eps_xx"], eps_yy=st["eps_yy"], fn_N=fn.tolist(), fn_p05_p95_N=q, broken_end=count_per_kind(br, kind),
               broken_contacts_end=np.flatnonzero(br).tolist(), wall_s=time.time() - t0, n_contacts=int(len(contacts)),
               n_particles=int(assembly.n_particles))
    res.setdefault("status", "finished")
    if log:
        log(f"{law:9s} free swelling ({pattern}{', damage' if damage else ''}): eps {st['eps_xx'] * 1e6:.2f} / {st['eps_yy'] * 1e6:.2f} e-6, "
            f"broken {res['broken_end']['total']}, {res['steps']} steps, {res['wall_s']:.1f} s")
    return res
