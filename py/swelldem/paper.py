# SPDX-License-Identifier: GPL-2.0-or-later
"""The vocabulary of the paper the model comes from, in one place: contact kinds, material data
(Tables 3.3 and 3.5), swelling kinetics (section 3.2) and the three swelling scenarios.

Plain Python (numpy only): the mesostructure generator, the YADE scenes, the scenarios, the
reports and the scripts all read these names from here. Units are in each name's comment.
"""
import numpy as np

# Contact kinds. The ids are those of ContactKind.kindId / SwellPhys.kindId in the plugin and of
# Assembly.kind in swelldem.meso (the Ip2 derives a contact's kind from the two materials).
MORTAR, ITZ, AGG = 0, 1, 2
KIND_NAMES = ("MORTAR", "ITZ", "AGG")
KIND_IDS = {name: k for k, name in enumerate(KIND_NAMES)}
#: Kinds swelldem adds for the conditions of structures (not the paper's): platens
#: (swelldem.dem.platens), reinforcing steel and its bond to the concrete (swelldem.dem.rebar).
STRUCTURE_KIND_IDS = {"PLATEN": 3, "STEEL": 4, "BOND": 5}

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


def larive_xi(t, kinetics="isr"):
    """Larive's sigmoid xi(t) = (1 - e^(-t/tau_c)) / (1 + e^(-(t - tau_L)/tau_c)) [-] of `kinetics`
    (a KINETICS key), t in days (scalar or array). Evaluated in numpy, so it is a reference
    independent of the plugin's own kinetics."""
    if kinetics not in KINETICS:
        raise ValueError(f"swelldem: kinetics = {kinetics!r} is out of range; allowed: {', '.join(KINETICS)}")
    tau_c, tau_l, _ = KINETICS[kinetics]
    t = np.asarray(t, dtype=float)
    return (1 - np.exp(-t / tau_c)) / (1 + np.exp(-(t - tau_l) / tau_c))
