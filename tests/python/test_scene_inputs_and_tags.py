# SPDX-License-Identifier: GPL-2.0-or-later
"""Numpy scalars as contact_kind inputs, and O.tags (a yade-batch job's description) kept by the
scene builder's O.reset()."""

SCRIPT = r"""
import numpy as np
from swelldem import dem, meso
k = dem.contact_kind("MORTAR", behaviour="elastic", young=np.float64(25e9), shear_ratio=np.float32(0.25),
                     swell_disp_inf=np.float64(1e-6), damage=np.bool_(True), tensile_strength=np.float64(3e6),
                     kelvinUnitsPerDecade=np.float64(2.0), residualFrictionAngle=np.array(0.1))
got = dict(young=k.young, shearRatio=k.shearRatio, swellDispInf=k.swellDispInf, damage=k.damage,
           tensileStrength=k.tensileStrength, kelvinUnitsPerDecade=k.kelvinUnitsPerDecade,
           residualFrictionAngle=k.residualFrictionAngle, swelling=k.swelling)
tags = {"description": "isr_seed3", "params": "seed=3,size_mm=(12,12)", "d.id": "isr_seed3.20260101T000000p1"}
for key, v in tags.items():
    O.tags[key] = v
a = meso.generate(seed=1, width_mm=12, height_mm=12)
kinds = {n: dem.contact_kind(n, young=60e9 if n == "AGG" else 30e9) for n in ("MORTAR", "ITZ", "AGG")}
dem.to_yade(a, kinds, dem.make_solver("adr", tStart=1, tEnd=10, stepsPerDecade=1))
dump(dict(kind=got, tags={key: O.tags[key] for key in tags}, bodies=len(O.bodies), n=a.n_particles))
"""


def test_numpy_scalars_and_batch_tags(yade_run):
    r = yade_run(SCRIPT, threads=1, timeout=300)
    assert r["kind"] == dict(young=25e9, shearRatio=float(__import__("numpy").float32(0.25)), swellDispInf=1e-6, damage=True,
                             tensileStrength=3e6, kelvinUnitsPerDecade=2.0, residualFrictionAngle=0.1, swelling=True)
    assert r["tags"] == {"description": "isr_seed3", "params": "seed=3,size_mm=(12,12)", "d.id": "isr_seed3.20260101T000000p1"}
    assert r["bodies"] == r["n"] > 0
