# SPDX-License-Identifier: GPL-2.0-or-later
"""Building blocks of swelldem scenes in YADE: the paper's material data, contact kinds, 2D discs
and the engine list. Import inside YADE (yade-swelldem), where the plugin classes exist."""
import yade
from yade import utils

# Paper Table 3.3, B3 coefficients q1..q4 in 1e-6/MPa (= 1e-12/Pa).
PAPER_B3 = {"mortar": (6.7, 108.1, 44.2, 14.3), "concrete": (9.0, 23.7, 46.6, 5.1), "itz": (19.3, 194.6, 72.9, 7.5)}
# Paper section 3.2: swelling kinetics of each reaction (tau_c, tau_L) [day] and the analysis end [day].
KINETICS = {"isr": (50.0, 100.0, 3650.0), "asr": (2500.0, 5000.0, 50000.0)}
KIND_IDS = {"MORTAR": 0, "ITZ": 1, "AGG": 2}
BEHAVIOURS = ("elastic", "aging-elastic", "viscoelastic")


def larive_xi(t, kinetics="isr"):
    """Larive's sigmoid xi(t) = (1 - e^(-t/tau_c)) / (1 + e^(-(t - tau_L)/tau_c)) of `kinetics` (a
    KINETICS key), t in days (scalar or array): evaluated here in numpy, as a reference independent
    of the plugin's SwellingKinetics."""
    import numpy as np
    tau_c, tau_l, _ = KINETICS[kinetics]
    t = np.asarray(t, dtype=float)
    return (1 - np.exp(-t / tau_c)) / (1 + np.exp(-(t - tau_l) / tau_c))


def contact_kind(name, behaviour="elastic", young=30e9, b3="mortar", shear_ratio=0.3, swell_disp_inf=0.0, kinetics="isr",
                 damage=False, tensile_strength=4e6, **extra):
    """A ContactKind with the paper's B3 q's of `b3` (a PAPER_B3 key) and kinetics of `kinetics`
    (a KINETICS key). Units: young [Pa], swell_disp_inf [m], tensile_strength [Pa]."""
    if behaviour not in BEHAVIOURS:
        raise ValueError(f"swelldem: behaviour = {behaviour!r} is out of range; allowed: {', '.join(BEHAVIOURS)}")
    if b3 not in PAPER_B3:
        raise ValueError(f"swelldem: b3 = {b3!r} is out of range; allowed: {', '.join(PAPER_B3)}")
    if kinetics not in KINETICS:
        raise ValueError(f"swelldem: kinetics = {kinetics!r} is out of range; allowed: {', '.join(KINETICS)}")
    q1, q2, q3, q4 = (q * 1e-12 for q in PAPER_B3[b3])
    tau_c, tau_l, _ = KINETICS[kinetics]
    swelling = bool(extra.pop("swelling", False)) or swell_disp_inf > 0  # a kind may swell through per-contact overrides only
    return yade.wrapper.ContactKind(name=name, kindId=KIND_IDS.get(name, 3), behaviour=behaviour, young=young, shearRatio=shear_ratio,
                                    q1=q1, q2=q2, q3=q3, q4=q4, swelling=swelling,
                                    swellDispInf=swell_disp_inf, tauC=tau_c, tauL=tau_l, damage=damage,
                                    tensileStrength=tensile_strength, **extra)


def disc(center_xy, radius, material, fixed=False):
    """A 2D disc: a YADE sphere in the plane z = 0 with z translation and x, y rotations blocked."""
    b = utils.sphere((center_xy[0], center_xy[1], 0.0), radius, material=material)
    b.state.blockedDOFs = "xyzXYZ" if fixed else "zXY"
    return b


def engines(ip2, solver, detection_factor=1.05):
    """ForceResetter, collider, InteractionLoop with swelldem's functors, then the ADR solver."""
    W = yade.wrapper
    return [W.ForceResetter(),
            W.InsertionSortCollider([W.Bo1_Sphere_Aabb(aabbEnlargeFactor=detection_factor)], verletDist=0, label="collider"),
            W.InteractionLoop([W.Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=detection_factor)], [ip2],
                              [W.Law2_ScGeom_SwellPhys_AgingSwelling()]),
            solver]


def run_to_end(solver, chunk=2000):
    """Runs until the solver has converged its last physical step (errors propagate)."""
    while not solver.finished:
        yade.wrapper.Omega().run(chunk, True)
