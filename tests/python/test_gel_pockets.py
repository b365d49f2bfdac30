# SPDX-License-Identifier: GPL-2.0-or-later
"""The gel pockets of ASR-coarse under each reading of the paper (swelldem.meso.gel_pockets,
--gel-pockets, --gel-displacement): which contacts they are, how far they swell, and the force
balance's bound on their forces, against references the drawing code does not compute."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO

from swelldem import meso, options, paper
from swelldem.meso import gel_pockets
from swelldem.scenario import SwellingTest


@pytest.fixture(scope="module")
def assembly():
    return meso.generate(seed=2, width_mm=30, height_mm=30)


def test_single_is_the_draw_before_the_readings(assembly):
    """'single' draws exactly what swelldem drew before the readings existed (choose_contacts), so
    --gel-pockets single --gel-displacement rule makes the runs of that time again; the default is
    the reading that matches the paper best (docs/scenarios.md)."""
    assert SwellingTest().gel_pockets == "rim" and SwellingTest().gel_displacement == "aggregate"
    np.testing.assert_array_equal(gel_pockets.choose(assembly, "single", 0.1, 5),
                                  meso.choose_contacts(assembly, "AGG", 0.1, 5))


def test_each_reading_draws_its_contacts(assembly):
    a = assembly
    kind = a.kind
    n_agg, n_itz = int((kind == meso.AGG).sum()), int((kind == meso.ITZ).sum())
    # the rim, from the contact list by a plain loop: particles with an ITZ contact
    itz_particles = set()
    for c in range(a.n_contacts):
        if kind[c] == meso.ITZ:
            itz_particles.update(int(p) for p in a.contacts[c])
    for reading in gel_pockets.READINGS:
        chosen = gel_pockets.choose(a, reading, 0.1, 5)
        again = gel_pockets.choose(a, reading, 0.1, 5)
        np.testing.assert_array_equal(chosen, again)                       # seeded
        assert not np.array_equal(chosen, gel_pockets.choose(a, reading, 0.1, 6))
        assert len(set(chosen.tolist())) == len(chosen)
        if reading == "with-itz":
            assert len(chosen) == round(0.1 * (n_agg + n_itz))
            assert set(kind[chosen].tolist()) == {meso.AGG, meso.ITZ}
            # the ITZ share of a uniform draw: binomial, within 4 standard deviations
            share, k = n_itz / (n_agg + n_itz), len(chosen)
            assert abs((kind[chosen] == meso.ITZ).sum() - share * k) < 4 * np.sqrt(k * share * (1 - share))
        else:
            assert len(chosen) == round(0.1 * n_agg)
            assert np.all(kind[chosen] == meso.AGG)
        if reading == "rim":
            assert all(int(a.contacts[c, 0]) in itz_particles or int(a.contacts[c, 1]) in itz_particles for c in chosen)


def _neighbours_within(a, chosen, radius):
    """Per chosen contact, how many other chosen contacts have their midpoint within `radius` of its own."""
    mid = np.column_stack([(a.x[a.contacts[chosen, 0]] + a.x[a.contacts[chosen, 1]]) / 2,
                           (a.y[a.contacts[chosen, 0]] + a.y[a.contacts[chosen, 1]]) / 2])
    d = np.linalg.norm(mid[:, None, :] - mid[None, :, :], axis=2)
    return (d <= radius).sum(axis=1) - 1


def test_clustered_pockets_are_small_areas(assembly):
    """Clustered pockets: a pocket contact has several others around it, where contacts drawn one
    by one have about the gel fraction of their neighbours (10 % of some 7 within 1 mm)."""
    a = assembly
    radius = 1e-3
    clustered = gel_pockets.choose(a, "clustered", 0.1, 5, radius)
    single = gel_pockets.choose(a, "single", 0.1, 5)
    n_c, n_s = _neighbours_within(a, clustered, radius).mean(), _neighbours_within(a, single, radius).mean()
    assert n_s < 1.5 and n_c > 3 * n_s, (n_c, n_s)
    # pockets 2 mm in radius: the same count, more neighbours each
    wide = gel_pockets.choose(a, "clustered", 0.1, 5, 2e-3)
    assert len(wide) == len(clustered)
    assert _neighbours_within(a, wide, 2e-3).mean() > 1.5 * _neighbours_within(a, clustered, 2e-3).mean()


def test_pocket_displacement_and_restrained_forces(assembly):
    a = assembly
    assert gel_pockets.pocket_displacement(0.8e-6, "rule", 0.1) == 0.8e-6
    assert gel_pockets.pocket_displacement(0.8e-6, "aggregate", 0.1) == pytest.approx(8e-6, rel=1e-15)
    chosen = gel_pockets.choose(a, "with-itz", 0.1, 3)
    young = {meso.AGG: 60e9, meso.ITZ: 10e9}
    full = gel_pockets.restrained_forces(a, chosen, 1e-6, young)
    for f, c in zip(full, chosen):
        e = 60e9 if a.kind[c] == meso.AGG else 10e9
        assert f == pytest.approx(-e * a.facet_area_m2[c] / a.distance_m[c] * 1e-6, rel=1e-12)
    # the bound: the 5 % quantile over every AGG contact, pockets at their restrained force, the rest at 0
    agg = np.nonzero(a.kind == meso.AGG)[0]
    forces = {int(c): 0.0 for c in agg}
    for f, c in zip(full, chosen):
        if a.kind[c] == meso.AGG:
            forces[int(c)] = f
    assert gel_pockets.quantile_bound(a, chosen, full) == pytest.approx(np.quantile(list(forces.values()), 0.05), rel=1e-12)


@pytest.mark.parametrize("kw, needle", [
    ({"gel_pockets": "everywhere"}, "gel_pockets = 'everywhere' is out of range; allowed: single, clustered, rim, with-itz"),
    ({"gel_pocket_radius_mm": 0.0}, "gel_pocket_radius_mm = 0.0 is out of range"),
    ({"gel_displacement": "paper"}, "gel_displacement = 'paper' is out of range; allowed: rule, aggregate"),
    ({"scenario": "asr-coarse", "gel_displacement": "aggregate", "gel_fraction": 0.0}, "gel_fraction = 0.0 is out of range"),
])
def test_bad_readings_are_refused(kw, needle):
    with pytest.raises(options.OptionError) as e:
        SwellingTest(**kw).validate()
    assert needle in str(e.value)


def test_a_fraction_beyond_the_rims_is_refused(assembly):
    rim = gel_pockets.rim_contacts(assembly)
    share = len(rim) / (assembly.kind == meso.AGG).sum()
    assert 0 < share < 0.9  # the outer layer of a 2 mm-particle aggregate: about half of its contacts
    assert len(gel_pockets.choose(assembly, "rim", share - 0.01, seed=1)) == gel_pockets.count(assembly, "rim", share - 0.01)
    with pytest.raises(ValueError) as e:
        gel_pockets.choose(assembly, "rim", 0.9, seed=1)
    assert f"gel_fraction = 0.9 is out of range for gel_pockets 'rim'" in str(e.value)
    assert f"allowed: gel_fraction <= {share:.3f}" in str(e.value)


def test_bad_reading_on_the_command_line_before_work(tmp_path):
    out = tmp_path / "run"
    proc = subprocess.run([os.path.join(REPO, "scripts", "yade-swelldem"), "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"),
                           "--scenario", "asr-coarse", "--gel-pockets", "rims", "--out", str(out)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2, proc.stderr[-2000:]
    assert "gel-pockets" in proc.stderr or "gel_pockets" in proc.stderr
    assert not out.exists()


FULL_RESTRAINT = r"""
import sys
sys.path.insert(0, sys.argv[1])
from swelldem import scenario, dem
t = scenario.SwellingTest(scenario='asr-coarse', behaviour='elastic', damage=False, size_mm=(12, 12), steps_per_decade=3,
                          gel_pockets=sys.argv[2], gel_displacement=sys.argv[3], out=sys.argv[4])
b = scenario.build(t)
for body in O.bodies:
    body.state.blockedDOFs = 'xyzXYZ'
dem.run_to_end(b.solver)
a = b.assembly
rows = []
for c, (i, j) in enumerate(b.scene.contacts):
    p = O.interactions[int(i), int(j)].phys
    rows.append([p.Fn, p.swellingDispInf, int(a.kind[c]), float(a.facet_area_m2[c]), float(a.distance_m[c])])
dump({'rows': rows, 'gel': [int(g) for g in b.gel], 't_end': b.solver.tEnd, 'r_mean': float(a.r.mean()),
      'young_agg': b.kinds['AGG'].young})
"""


@pytest.mark.parametrize("reading, displacement", [("clustered", "aggregate"), ("with-itz", "rule")])
def test_fully_restrained_pockets_carry_the_closed_form(yade_run, tmp_path, reading, displacement):
    """Every particle held: each pocket's force is the closed form -E A / L x d x (xi(t_end) - xi(1 d))
    (E of its kind; ITZ pockets of 'with-itz' at their aging modulus, so only their sign and that
    they alone swell besides the AGG pockets are checked), every other contact carries nothing,
    and d is Table 3.2's rule, or that over the gel fraction for 'aggregate'."""
    res = yade_run(FULL_RESTRAINT, os.path.join(REPO, "py"), reading, displacement, tmp_path / "run", threads=1)
    rows = np.array(res["rows"])
    fn, d_inf, kind, area, length = rows.T
    gel = np.array(res["gel"], dtype=int)
    d_rule = 1000e-6 * 2 * res["r_mean"]
    d = d_rule / 0.1 if displacement == "aggregate" else d_rule
    dxi = paper.larive_xi(res["t_end"], "asr") - paper.larive_xi(1.0, "asr")
    pocket = np.zeros(len(rows), dtype=bool)
    pocket[gel] = True
    assert np.allclose(d_inf[gel], d, rtol=1e-12)
    drawn_from = (kind == meso.AGG) | (kind == meso.ITZ) if reading == "with-itz" else kind == meso.AGG
    assert np.all(d_inf[~pocket & drawn_from] == 0)
    agg = pocket & (kind == meso.AGG)
    expected = -res["young_agg"] * area[agg] / length[agg] * d * dxi
    np.testing.assert_allclose(fn[agg], expected, rtol=1e-9)
    assert np.all(fn[pocket & (kind == meso.ITZ)] < 0)
    assert np.max(np.abs(fn[~pocket])) <= 1e-9 * np.max(np.abs(expected))


def test_free_specimen_pockets_stay_within_the_bound(tmp_path):
    """A free elastic specimen: each pocket's restraint degree (its force over the fully restrained
    one) lies in [0, 1], and the AGG 5 % quantile is no lower than the force balance's bound
    recorded before the run."""
    out = tmp_path / "free"
    proc = subprocess.run([os.path.join(REPO, "scripts", "yade-swelldem"), "-j", "1", "-n", "-x",
                           os.path.join(REPO, "scripts", "swelling_test.py"), "--scenario", "asr-coarse", "--behaviour", "elastic",
                           "--no-damage", "--size-mm", "20", "20", "--steps-per-decade", "3", "--gel-pockets", "clustered",
                           "--gel-displacement", "aggregate", "--out", str(out)], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "bound on the AGG 5 % quantile" in proc.stdout
    res = json.loads((out / "results.json").read_text())
    g = res["gel_pockets"]
    assert g["reading"] == "clustered" and g["displacement"] == "aggregate" and g["n"] == res["n_gel_pockets"]
    lo, med, hi = g["restraint_q05_q50_q95"]
    assert 0 < lo <= med <= hi <= 1
    assert res["per_kind"]["AGG"]["fn_p05_kN"][-1] >= g["agg_p05_bound_run_kN"]
    # the tables name a reading away from the default (rim) among the run's conditions
    from swelldem import report
    assert "gel_pockets=clustered" in " ".join(report.run_conditions(res))


def test_runs_made_before_the_readings_read_as_single_and_rule(tmp_path):
    """A results.json whose config has no gel_pockets / gel_displacement (made before the readings
    existed) drew its pockets one by one at Table 3.2's d: the tables and a study's resume read it so,
    whatever today's defaults."""
    from swelldem import report, study
    cfg = {"scenario": "asr-coarse", "seed": 1}
    res = {"scenario": "asr-coarse", "behaviour": "elastic", "damage": False, "status": "finished", "config": dict(cfg)}
    path = tmp_path / "results.json"
    path.write_text(json.dumps(res))
    try:
        loaded = report.load_results(str(path))
    except report.ResultsError:  # a partial file: the reading of the config is what is tested
        loaded = report.current_form(json.loads(path.read_text()))
    assert loaded["config"]["gel_pockets"] == "single" and loaded["config"]["gel_displacement"] == "rule"
    assert study.differing(cfg, {"gel_pockets": "single", "gel_displacement": "rule"}) == {}
    assert study.differing(cfg, {"gel_displacement": "aggregate"}) == {"gel_displacement": ("rule", "aggregate")}
