# SPDX-License-Identifier: GPL-2.0-or-later
"""The vocabulary of the paper the model comes from, in one place: contact kinds, material data
(Tables 3.3 and 3.5), swelling kinetics (section 3.2) and the three swelling scenarios.

Plain Python (numpy only): the mesostructure generator, the YADE scenes, the scenarios, the
reports and the scripts all read these names from here. Units are in each name's comment.
"""
import math

import numpy as np

# Contact kinds. The ids are those of ContactKind.kindId / SwellPhys.kindId in the plugin and of
# Assembly.kind in swelldem.meso (the Ip2 derives a contact's kind from the two materials).
MORTAR, ITZ, AGG = 0, 1, 2
KIND_NAMES = ("MORTAR", "ITZ", "AGG")
KIND_IDS = {name: k for k, name in enumerate(KIND_NAMES)}
#: Kinds swelldem adds for the conditions of structures (not the paper's): platens
#: (swelldem.dem.platens), reinforcing steel and its bond to the concrete (swelldem.dem.rebar).
STRUCTURE_KIND_IDS = {"PLATEN": 3, "STEEL": 4, "BOND": 5}
#: Every kind name by its id (kindId), the paper's three and the structures'.
KIND_NAME_OF_ID = {**{k: name for k, name in enumerate(KIND_NAMES)}, **{k: name for name, k in STRUCTURE_KIND_IDS.items()}}

#: Table 3.3: B3 basic-creep coefficients (q1, q2, q3, q4) [1e-6/MPa = 1e-12/Pa] of each material.
B3_Q = {"mortar": (6.7, 108.1, 44.2, 14.3), "concrete": (9.0, 23.7, 46.6, 5.1), "itz": (19.3, 194.6, 72.9, 7.5)}
#: The Table 3.3 material of the contact kinds that creep (aggregate contacts are linear elastic).
B3_OF_KIND = {"MORTAR": "mortar", "ITZ": "itz"}

#: Table 3.5: tensile strength f_t [Pa] of each contact kind (Fn,max = f_t x facet area).
TENSILE_STRENGTH = {"MORTAR": 4e6, "ITZ": 2e6, "AGG": 6e6}

#: Contact modulus of aggregate contacts [Pa]: a sound siliceous or calcareous aggregate. The paper
#: gives none; this is swelldem's assumption (docs/scenarios.md).
AGGREGATE_YOUNG = 60e9

#: Section 3.2: Larive kinetics of each reaction, (tau_c [day], tau_L [day], end of the analysis [day]).
KINETICS = {"isr": (50.0, 100.0, 3650.0), "asr": (2500.0, 5000.0, 50000.0)}

#: Table 3.2: ultimate free swelling strain of the swelling material [-] (d_inf = EPS_INF x 2 R_mean).
EPS_INF = 1000e-6
#: Table 3.2's result: the free swelling strain [-] of its random mortar assembly at the end of the
#: analysis (3650 days ISR, 50000 days ASR; the same figure for both), with d_inf = EPS_INF x 2 R_mean.
TABLE_3_2_EPS_FINAL = 1061e-6
#: Table 3.2: mean particle radius [m] of that assembly (Rmax = 0.48 mm, Rmin/Rmax = 2/3).
TABLE_3_2_R_MEAN = 0.397e-3

#: The paper's three swelling tests: kinetics (a KINETICS key) and the contact kinds whose every
#: contact swells. In 'asr-coarse' none does: a seeded fraction of the AGG contacts (gel pockets) swells.
SCENARIOS = {
    "isr": {"kinetics": "isr", "swelling_kinds": ("MORTAR", "ITZ")},
    "asr-fine": {"kinetics": "asr", "swelling_kinds": ("MORTAR",)},
    "asr-coarse": {"kinetics": "asr", "swelling_kinds": ()},
}


#: Section 3.5.1's gel pockets of 'asr-coarse', read from the paper's two sentences on them:
#: "swelling due to ASR-coarse agg. type reactions originates from small areas of the aggregate,
#: gel pockets (inside and near the boundary)" (3.1) and "only 10% of the coarse aggregates
#: contacts had swelling" (3.5.1). The text leaves open which contacts those are; each reading is
#: a --gel-pockets choice (swelldem.meso.gel_pockets draws them), with what it takes from the text.
#: The default, 'rim' with the 'aggregate' displacement, is the reading that matches the
#: paper's ASR-coarse rows best (docs/scenarios.md, "Readings of the paper's open choices").
GEL_POCKET_READINGS = {
    "single": "contacts drawn one by one, at random, among all aggregate (AGG) contacts: '10% of the coarse "
              "aggregates contacts'",
    "clustered": "pockets of neighbouring AGG contacts (those within gel_pocket_radius_mm of a drawn centre), "
                 "drawn until they hold the fraction: 'small areas of the aggregate, gel pockets'",
    "rim": "contacts drawn one by one among the AGG contacts of the aggregate's outer particle layer (a "
           "particle with an ITZ contact): 'near the boundary'",
    "with-itz": "contacts drawn one by one among the AGG and the ITZ contacts: 'coarse aggregates contacts' "
                "read as every contact of an aggregate particle, its interface included",
}
#: The pockets' ultimate swelling displacement d_inf, which the paper's Table 3.2 gives for mortar
#: and ITZ only: 'rule', the same eps_inf x 2 R_mean (Table 3.2's rule); 'aggregate', that value over
#: the gel fraction, so that the aggregate as a whole would swell freely by eps_inf (the stiffness-
#: weighted mean of the contacts' swelling strains d/L is the network's free strain).
GEL_DISPLACEMENT_READINGS = {
    "rule": "eps_inf x 2 R_mean, Table 3.2's rule for mortar and ITZ",
    "aggregate": "eps_inf x 2 R_mean / gel_fraction: the aggregate as a whole swells freely by eps_inf",
}


def larive_xi(t, kinetics="isr"):
    """Larive's sigmoid xi(t) = (1 - e^(-t/tau_c)) / (1 + e^(-(t - tau_L)/tau_c)) [-] of `kinetics`
    (a KINETICS key), t in days (scalar or array). Evaluated in numpy, so it is a reference
    independent of the plugin's own kinetics."""
    if kinetics not in KINETICS:
        raise ValueError(f"swelldem: kinetics = {kinetics!r} is out of range; allowed: {', '.join(KINETICS)}")
    tau_c, tau_l, _ = KINETICS[kinetics]
    t = np.asarray(t, dtype=float)
    return (1 - np.exp(-t / tau_c)) / (1 + np.exp(-(t - tau_l) / tau_c))


#: The paper's specimen: width and height [mm] (section 3.3); runs of another size say so in their tables.
SPECIMEN_SIZE_MM = (100.0, 100.0)

#: Short names of the contact behaviours in run folders and table keys: 'el' the elastic (aging
#: modulus) runs, 've' the aging viscoelastic ones; the paper's words for them.
BEHAVIOUR_KEYS = {"el": "elastic", "ve": "viscoelastic"}
BEHAVIOUR_WORDS = {"el": "elastic", "ve": "aging viscoelastic"}
#: The damage settings of the study: 'nodmg' (paper 3.5.1-3.5.2, Table 3.4) and 'dmg' (3.5.3-3.5.5, Table 3.6).
DAMAGE_KEYS = {"nodmg": False, "dmg": True}


def _forces(p05, p95, broken=0, broken_pct=0.0):
    return {"p05": p05, "p95": p95, "broken": broken, "broken_pct": broken_pct}


#: Tables 3.4 (no damage) and 3.6 (damage): at the last step, per (scenario, 'el'|'ve',
#: 'nodmg'|'dmg') and contact kind, the 5 % and 95 % normal-force quantiles 'p05', 'p95' [kN]
#: and the broken contacts 'broken' [-] and their share 'broken_pct' [%] of the kind's contacts.
TABLE_FORCES = {
    ("isr", "el", "nodmg"): {"MORTAR": _forces(-8.3, 2.5), "ITZ": _forces(-3.7, 6.3), "AGG": _forces(0.0, 8.4)},
    ("isr", "ve", "nodmg"): {"MORTAR": _forces(-2.0, 0.6), "ITZ": _forces(-1.6, 1.9), "AGG": _forces(-0.5, 3.1)},
    ("asr-fine", "el", "nodmg"): {"MORTAR": _forces(-13.5, 3.8), "ITZ": _forces(-1.6, 0.6), "AGG": _forces(0.5, 1.2)},
    ("asr-fine", "ve", "nodmg"): {"MORTAR": _forces(-3.4, 1.0), "ITZ": _forces(-0.7, 3.3), "AGG": _forces(-0.2, 3.7)},
    ("asr-coarse", "el", "nodmg"): {"MORTAR": _forces(-1.9, 3.6), "ITZ": _forces(-8.6, 4.6), "AGG": _forces(-55.4, 30.7)},
    ("asr-coarse", "ve", "nodmg"): {"MORTAR": _forces(-0.7, 1.1), "ITZ": _forces(-3.2, 1.9), "AGG": _forces(-47.7, 31.8)},
    ("isr", "el", "dmg"): {"MORTAR": _forces(-1.5, 1.4, 2406, 12.4), "ITZ": _forces(0.0, 0.0, 4568, 90.3), "AGG": _forces(-0.4, 0.5, 1540, 16.2)},
    ("isr", "ve", "dmg"): {"MORTAR": _forces(-1.1, 0.7, 85, 0.4), "ITZ": _forces(-0.7, 0.8, 3456, 68.3), "AGG": _forces(-0.7, 1.6, 219, 2.3)},
    ("asr-fine", "el", "dmg"): {"MORTAR": _forces(-1.6, 1.5, 2636, 13.6), "ITZ": _forces(0.0, 0.0, 4980, 98.5), "AGG": _forces(0.0, 0.0, 585, 6.2)},
    ("asr-fine", "ve", "dmg"): {"MORTAR": _forces(-0.7, 0.6, 213, 1.1), "ITZ": _forces(-0.1, 0.3, 4346, 85.9), "AGG": _forces(-0.3, 0.7, 279, 2.9)},
    ("asr-coarse", "el", "dmg"): {"MORTAR": _forces(-0.4, 0.4, 4128, 21.3), "ITZ": _forces(-0.3, 0.2, 3107, 61.4),
                                  "AGG": _forces(-0.5, 0.5, 2995, 31.5)},
    ("asr-coarse", "ve", "dmg"): {"MORTAR": _forces(-0.6, 0.9, 1492, 7.7), "ITZ": _forces(-1.4, 0.6, 1871, 37.0),
                                  "AGG": _forces(-1.9, 1.1, 2925, 30.8)},
}

#: The paper's "variation to reference contact behaviour" columns [%], (value - reference) /
#: reference of the 5 % and 95 % quantiles (and, in Table 3.6, of the broken count); None where the
#: paper prints "-" (a reference of 0.0). Per table, scenario and kind:
#: '3.4': aging viscoelastic against elastic, no damage; '3.6': aging viscoelastic against elastic,
#: both with damage (5 %, 95 %, broken); '3.7': aging viscoelastic with damage against elastic
#: without damage (Table 3.7's viscoelastic no-damage rows repeat Table 3.4's).
VARIATION = {
    "3.4": {"isr": {"MORTAR": (-76, -76), "ITZ": (-57, -70), "AGG": (None, -63)},
            "asr-fine": {"MORTAR": (-75, -74), "ITZ": (-56, -69), "AGG": (-140, -67)},
            "asr-coarse": {"MORTAR": (-63, -69), "ITZ": (-63, -59), "AGG": (-14, 4)}},
    "3.6": {"isr": {"MORTAR": (-27, -50, -96), "ITZ": (None, None, -24), "AGG": (75, 220, -86)},
            "asr-fine": {"MORTAR": (-56, -60, -92), "ITZ": (None, None, -13), "AGG": (None, None, -52)},
            "asr-coarse": {"MORTAR": (50, 125, -64), "ITZ": (367, 200, -40), "AGG": (280, 120, -2)}},
    "3.7": {"isr": {"MORTAR": (-87, -72), "ITZ": (-81, -87), "AGG": (None, -81)},
            "asr-fine": {"MORTAR": (-95, -84), "ITZ": (-94, -97), "AGG": (-160, -94)},
            "asr-coarse": {"MORTAR": (-68, -75), "ITZ": (-84, -87), "AGG": (-97, -96)}},
}


#: Arrhenius constants of Larive's kinetics (activation energy over R [K]) and their reference
#: temperature [K] (Larive 1998; Ulm et al. 2000), the ContactKind defaults.
LARIVE_UC, LARIVE_UL, LARIVE_T0 = 5400.0, 9400.0, 293.15


def larive_xi_under(t, tau_c, tau_l, days=(), temperatures_K=(), T0=LARIVE_T0, Uc=LARIVE_UC, UL=LARIVE_UL):
    """Larive's swelling ratio xi [-] at times t [day] under a temperature history (days [day],
    temperatures_K [K], linear in between, held before the first and after the last; none: T0
    throughout), tau_c and tau_L [day] being the values at T0 and tau(T) = tau(T0) exp(U (1/T - 1/T0)).
    At one temperature the closed form of that temperature; under a history Larive's ODE
    t_c dxi/dt + xi = 1, t_c = tau_c (1 + e^(-tau_L/tau_c)) / (xi + e^(-tau_L/tau_c)), integrated from
    xi(0) = 0 by scipy (tolerance 1e-10). Evaluated in numpy/scipy, independent of the plugin."""
    t = np.asarray(t, dtype=float)
    scale = lambda T, U: np.exp(U * (1.0 / np.asarray(T, dtype=float) - 1.0 / T0))  # noqa: E731
    if len(days) <= 1:
        T = temperatures_K[0] if len(days) else T0
        tc, tl = tau_c * scale(T, Uc), tau_l * scale(T, UL)
        return (1 - np.exp(-t / tc)) / (1 + np.exp(-(t - tl) / tc))
    from scipy.integrate import solve_ivp

    def rate(time, xi):
        T = np.interp(time, days, temperatures_K)
        tc, tl = tau_c * scale(T, Uc), tau_l * scale(T, UL)
        e = math.exp(-tl / tc)
        return (1 - xi) * (xi + e) / (tc * (1 + e))

    flat = t.ravel()
    sol = solve_ivp(rate, (0.0, float(flat.max(initial=0.0))), [0.0], method="LSODA", rtol=1e-10, atol=1e-12, dense_output=True)
    return np.clip(sol.sol(flat)[0], 0.0, 1.0).reshape(t.shape)
