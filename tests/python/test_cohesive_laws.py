# SPDX-License-Identifier: GPL-2.0-or-later
"""swelldem's law (elastic-brittle: creep and swelling off) against YADE's stock cohesive laws
matched per contact (issue 8, docs/cohesive-laws.md), real YADE on a small concrete specimen.

Why the tolerances are tight: with the same kn, ks on every bond, the same stress-free distance,
the same tensile force f_t A, no moment transfer and no shear limit on intact bonds, the two
laws compute the same contact forces from the same kinematics; the discs, masses, dt, loading
and NewtonIntegrator are identical, so the trajectories are the same up to the order of
floating-point operations. JCFpm (ScGeom, force and torque added as ours) agrees to 1e-6 (TOL);
CohFrictPhys, which needs the ScGeom6D geometry functor and applies its force at the contact point,
was measured 3e-6 off in modulus and 8e-6 in the first-break stress on this specimen (a small
systematic difference of that code path, not isolated further), hence 1e-4 for it: still 100
times smaller than what a 1 % stiffness or strength mismatch would give. The first break is a
threshold crossing of the same force on the same contact: the same contacts break in the same
recording interval (10 steps).
"""
import os

import pytest

from conftest import REPO

# The study module lives beside its script (scripts/cohesive/), not in the library.
STUDY = f"import sys\nsys.path.insert(0, {os.path.join(REPO, 'scripts', 'cohesive')!r})\nimport cohesive_laws as cc\n"

TOL = {"jcfpm": 1e-6, "cohfrict": 1e-4}

SCRIPT = STUDY + r"""
from swelldem import meso
a = meso.generate(seed=3, width_mm=12, height_mm=12, aggregate_area_fraction=0.2, wall_gap_mm=0.3)
moduli = cc.contact_moduli(0.38)
out = {'kinds': [int((a.kind == k).sum()) for k in range(3)]}
for law in sys.argv[1:]:
    info = cc.build(law, a, moduli, damping=0.6)
    r = cc.run_uniaxial(law, a, info, 'tension', deps_per_step=2e-8, chunk=10, drop=0.9)
    out[law] = {k: r[k] for k in ('modulus_Pa', 'peak_stress_Pa', 'strain_at_peak', 'first_break', 'dt_s', 'status', 'broken_at_peak')}
    out[law]['kn'] = info['kn'].tolist()
dump(out)
"""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from conftest import YadeRun
    return YadeRun(tmp_path_factory.mktemp("cohesive"))(SCRIPT, "swelldem", "cohfrict", "jcfpm", threads=1, timeout=300)


def test_specimen_has_all_kinds(runs):
    assert min(runs["kinds"]) > 10, runs["kinds"]


@pytest.mark.parametrize("law", ["cohfrict", "jcfpm"])
def test_same_elastic_modulus(runs, law):
    ours, stock = runs["swelldem"], runs[law]
    assert ours["dt_s"] == stock["dt_s"]
    assert 5e9 < ours["modulus_Pa"] < 1e11
    assert abs(stock["modulus_Pa"] / ours["modulus_Pa"] - 1) < TOL[law]


@pytest.mark.parametrize("law", ["cohfrict", "jcfpm"])
def test_same_first_break(runs, law):
    ours, stock = runs["swelldem"]["first_break"], runs[law]["first_break"]
    assert ours is not None and stock is not None
    assert ours["step"] == stock["step"]
    assert ours["contacts"] == stock["contacts"]
    assert abs(stock["stress"] / ours["stress"] - 1) < TOL[law]
    assert ours["stress"] > 0 and runs["swelldem"]["status"] == "post_peak"


CPM_SCRIPT = STUDY + r"""
from swelldem import meso
a = meso.generate(seed=3, width_mm=12, height_mm=12, aggregate_area_fraction=0.2, wall_gap_mm=0.3)
moduli = cc.contact_moduli(0.38)
ref = cc.run_uniaxial('swelldem', a, cc.build('swelldem', a, moduli), 'tension', deps_per_step=2e-8)
p = cc.calibrate_cpm(a, moduli, ref['modulus_Pa'], ref['peak_stress_Pa'], 2e-8, 0.6, iterations=1, log=lambda m: None)
r = cc.run_uniaxial('cpm', a, cc.build('cpm', a, moduli, cpm=p), 'tension', deps_per_step=2e-8)
dump({'ref': {k: ref[k] for k in ('modulus_Pa', 'peak_stress_Pa')}, 'cpm': {k: r[k] for k in ('modulus_Pa', 'peak_stress_Pa', 'status', 'first_damage_strain', 'strain_at_peak')},
      'young': p['young'], 'modulus_per_30GPa': p['modulus_per_30GPa']})
"""


def test_cpm_calibrated_to_our_modulus_and_peak(tmp_path):
    """Cpm is calibrated, not matched: young from an undamaged (neverDamage) run, epsCrackOnset from
    one damaging run scaled by the ratio of peaks. The check is that the calibrated, damaging Cpm
    run then reproduces our modulus and tensile peak within 2 % (measured 0.4 % and 0.3 %): this
    holds only if Cpm's elastic range in the damaging run is that of the undamaged run (with an
    absolute sigmaT of 3.5 MPa at young ~1e14 Pa every bond slid in shear and the slope came out
    10 times lower) and if its peak scales with epsCrackOnset."""
    from conftest import YadeRun
    out = YadeRun(tmp_path)(CPM_SCRIPT, threads=1, timeout=300)
    ref, cpm = out["ref"], out["cpm"]
    assert 1e13 < out["young"] < 1e15  # 2D, 1 m thick: Cpm's cross-section pi r^2 is ~1000 x below the facet area
    assert abs(cpm["modulus_Pa"] / ref["modulus_Pa"] - 1) < 0.02, (cpm, ref)
    assert abs(cpm["peak_stress_Pa"] / ref["peak_stress_Pa"] - 1) < 0.02, (cpm, ref)
    assert cpm["status"] == "post_peak"
    assert 0 < cpm["first_damage_strain"] < cpm["strain_at_peak"]  # Cpm damages gradually before its peak


SWELL_SCRIPT = STUDY + r"""
import numpy as np
from swelldem import meso
a = meso.generate(seed=3, width_mm=12, height_mm=12, aggregate_area_fraction=0.2, wall_gap_mm=0.3)
moduli = cc.contact_moduli(0.38)
out = {}
for law in ('swelldem', 'jcfpm', 'cohfrict'):
    r = cc.free_swelling(law, a, moduli, pattern='mortar', damage=False, tolerance=1e-8)
    out[law] = {k: r[k] for k in ('eps_xx', 'eps_yy', 'fn_N', 'status', 'broken_end', 'xi_fraction')}
dump(out)
"""


def test_free_swelling_same_as_radius_growth(tmp_path):
    """Free swelling, mortar discs swelling and aggregates not, no damage. swelldem swells each
    contact by its own law (Larive kinetics over log time, ADR); the stock laws have no swelling,
    so their radii are grown by the same final amount. The rest length of every bond then grows
    by g_i r_i + g_j r_j in both, and the end states solve the same elastic problem: the strain
    and every contact force must agree up to the solvers' tolerance (measured 1.2e-5 in strain and
    1.9e-4 of the largest force at 1e-9; a wrong swelling fraction or rest length would show at
    the 1e-2 level). The restraint by the aggregates makes the strain lower than eps_inf and
    leaves forces of either sign."""
    import numpy as np
    from conftest import YadeRun
    out = YadeRun(tmp_path)(SWELL_SCRIPT, threads=1, timeout=300)
    ours = out["swelldem"]
    f0 = np.array(ours["fn_N"])
    assert 0.99 < ours["xi_fraction"] < 1.0
    assert 300e-6 < ours["eps_xx"] < 1000e-6 and 300e-6 < ours["eps_yy"] < 1000e-6
    assert f0.min() < 0 < f0.max()
    for law in ("jcfpm", "cohfrict"):
        r = out[law]
        assert r["status"] == "finished" and r["broken_end"]["total"] == 0
        assert abs(r["eps_xx"] / ours["eps_xx"] - 1) < 1e-4 and abs(r["eps_yy"] / ours["eps_yy"] - 1) < 1e-4, (law, r["eps_xx"], ours["eps_xx"])
        assert np.max(np.abs(np.array(r["fn_N"]) - f0)) < 1e-3 * np.max(np.abs(f0)), law


DAMAGE_SWELL_SCRIPT = STUDY + r"""
from swelldem import meso
a = meso.generate(seed=3, width_mm=12, height_mm=12, aggregate_area_fraction=0.2, wall_gap_mm=0.3)
moduli = cc.contact_moduli(0.38)
out = {'swelldem': cc.free_swelling('swelldem', a, moduli, damage=True, tolerance=1e-4)['broken_end']}
for law in ('jcfpm', 'cohfrict'):
    out[law] = cc.free_swelling(law, a, moduli, damage=True, tolerance=1e-5)['broken_end']
dump(out)
"""


def test_free_swelling_cracking_like_slow_loading(tmp_path):
    """Free swelling of the mortar with damage: our ADR, at its default 10 steps a decade and
    tolerance 1e-4, against the stock laws loaded slowly (radius growth over 4000 damped Newton
    steps; 40000 gave the same count). Cracking is path-dependent and each break a threshold, so
    counts are compared, not contacts: ours within 30 % of theirs (measured 53 against 50-51). When
    the ADR let contacts break in its fictitious transients it gave 97 (86 at tolerance 1e-6)."""
    from conftest import YadeRun
    out = YadeRun(tmp_path)(DAMAGE_SWELL_SCRIPT, threads=1, timeout=300)
    stock = 0.5 * (out["jcfpm"]["total"] + out["cohfrict"]["total"])
    assert stock > 20, out
    assert abs(out["swelldem"]["total"] / stock - 1) < 0.3, out
    assert out["swelldem"]["ITZ"] > out["swelldem"]["MORTAR"], out  # debonding around the aggregates first
