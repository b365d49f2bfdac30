# SPDX-License-Identifier: GPL-2.0-or-later
"""An Assembly in real YADE with the real plugin (swelldem.dem.to_yade), the macroscopic strain
measure (swelldem.measure) on synthetic fields, and a small run of the paper's Table 3.2 check
(scripts/table_3_2.py). About 20 s on 2 cores."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

from conftest import LAUNCHER, REPO, build_dir

from swelldem import measure, meso, paper  # noqa: E402  (conftest puts py/ on the path)

TABLE_SCRIPT = os.path.join(REPO, "scripts", "table_3_2.py")


# ------------------------------------------------------------------ measure (plain numpy)

def _cloud(n=400, seed=0, w=0.02, h=0.015):
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(0, w, n), rng.uniform(0, h, n)])


def _affine(X, G, c, theta=0.0):
    """Displaced positions: strain-like gradient G, then a rigid rotation theta and translation c."""
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    Y = X + X @ np.asarray(G).T
    return Y @ R.T + np.asarray(c)


def test_affine_strain_recovers_an_affine_field_exactly():
    X = _cloud()
    G = [[1.2e-3, 0.3e-3], [0.1e-3, -0.4e-3]]
    f = measure.affine_strain(X, _affine(X, G, (1e-4, -3e-5)))
    assert f["eps_xx"] == pytest.approx(1.2e-3, rel=1e-9)
    assert f["eps_yy"] == pytest.approx(-0.4e-3, rel=1e-9)
    assert f["eps_xy"] == pytest.approx(0.2e-3, rel=1e-9)
    assert f["rotation"] == pytest.approx(-0.1e-3, rel=1e-9)
    assert f["eps_mean"] == pytest.approx(0.4e-3, rel=1e-9) and f["eps_vol"] == pytest.approx(0.8e-3, rel=1e-9)
    assert f["residual_rms"] < 1e-15


def test_affine_strain_in_3d_recovers_an_affine_field_exactly():
    rng = np.random.default_rng(3)
    X = rng.uniform(0, 0.01, (300, 3))
    G = np.array([[1.2e-3, 0.3e-3, -0.2e-3], [0.1e-3, -0.4e-3, 0.5e-3], [0.0, 0.2e-3, 0.7e-3]])
    f = measure.affine_strain(X, X + X @ G.T + np.array([1e-4, -3e-5, 2e-5]))
    for key, want in (("eps_xx", 1.2e-3), ("eps_yy", -0.4e-3), ("eps_zz", 0.7e-3), ("eps_xy", 0.2e-3),
                      ("eps_xz", -0.1e-3), ("eps_yz", 0.35e-3), ("eps_vol", 1.5e-3), ("eps_mean", 0.5e-3)):
        assert f[key] == pytest.approx(want, rel=1e-9), key
    assert f["rotation"] == pytest.approx([-0.15e-3, -0.1e-3, -0.1e-3], rel=1e-9)
    assert f["residual_rms"] < 1e-15
    with pytest.raises(ValueError, match="at least 4"):
        measure.affine_strain(X[:3], X[:3])
    with pytest.raises(ValueError, match="coplanar"):
        flat = X.copy()
        flat[:, 2] = 0
        measure.affine_strain(flat, flat)


def test_rigid_motion_gives_no_strain():
    X = _cloud(seed=1)
    f = measure.affine_strain(X, _affine(X, np.zeros((2, 2)), (0.3, 0.1), theta=1e-4))
    # A finite rotation theta is affine with gradient R - I: its symmetric part is cos(theta) - 1 ~ -theta^2/2.
    for k in ("eps_xx", "eps_yy"):
        assert abs(f[k]) < 1e-8
    assert abs(f["eps_xy"]) < 1e-15
    assert f["rotation"] == pytest.approx(1e-4, rel=1e-6)
    s = measure.side_strain(X, _affine(X, np.zeros((2, 2)), (0.3, 0.1)), 0.5e-3)
    assert abs(s["eps_x"]) < 1e-12 and abs(s["eps_y"]) < 1e-12


def test_isotropic_swelling_with_noise_and_weights():
    X = _cloud(n=2000, seed=2)
    rng = np.random.default_rng(5)
    cur = _affine(X, 1000e-6 * np.eye(2), (0, 0)) + rng.normal(0, 0.2e-6, X.shape)  # 2e-7 m ~ 1 % of the displacements
    f = measure.affine_strain(X, cur)
    # Standard error of the slope: sigma / (sqrt(n) std(X)) ~ 2e-7 / (45 x 5.8e-3) ~ 8e-7.
    assert f["eps_xx"] == pytest.approx(1000e-6, abs=4e-6) and f["eps_yy"] == pytest.approx(1000e-6, abs=5e-6)
    fw = measure.affine_strain(X, cur, weights=np.full(len(X), 3.0))
    assert fw["eps_xx"] == pytest.approx(f["eps_xx"], rel=1e-12)
    s = measure.side_strain(X, cur, 0.5e-3)
    assert s["eps_x"] == pytest.approx(1000e-6, abs=3e-5) and s["eps_y"] == pytest.approx(1000e-6, abs=4e-5)


def test_robust_fit_ignores_a_few_loose_particles():
    X = _cloud(n=500, seed=3)
    cur = _affine(X, np.diag([800e-6, 1200e-6]), (0, 0))
    cur[:10] += 5e-5  # 2 % rattlers displaced by ~3 times the largest swelling displacement
    plain = measure.affine_strain(X, cur)
    rob = measure.affine_strain(X, cur, robust=True)
    assert rob["eps_xx"] == pytest.approx(800e-6, rel=2e-3) and rob["eps_yy"] == pytest.approx(1200e-6, rel=2e-3)
    assert abs(plain["eps_xx"] - 800e-6) > 5 * abs(rob["eps_xx"] - 800e-6)
    assert rob["iterations"] >= 1


def test_measure_errors():
    X = _cloud(n=10)
    with pytest.raises(ValueError, match="shape"):
        measure.affine_strain(X, X[:5])
    with pytest.raises(ValueError, match="collinear"):
        line = np.column_stack([np.linspace(0, 1, 10), np.zeros(10)])
        measure.affine_strain(line, line)
    with pytest.raises(ValueError, match="at least 3"):
        measure.affine_strain(X[:2], X[:2])
    with pytest.raises(ValueError, match="non-finite"):
        Y = X.copy()
        Y[0, 0] = np.nan
        measure.affine_strain(X, Y)
    with pytest.raises(ValueError, match="weights"):
        measure.affine_strain(X, X, weights=-np.ones(10))


# ------------------------------------------------------------------ to_yade in real YADE

def test_to_yade_outside_yade_is_a_clear_error():
    from swelldem import dem
    a = meso.generate(seed=1, width_mm=6, height_mm=6, aggregate_area_fraction=0)
    with pytest.raises(dem.YadeUnavailableError, match="yade-swelldem"):
        dem.to_yade(a, {}, None)


def test_geometry_package_imports_no_yade_code():
    """swelldem.meso (and the vocabulary, swelldem.paper) run in plain Python: importing them and
    generating an assembly loads no YADE module, so the geometry stays usable without YADE."""
    code = ("import sys\n"
            "from swelldem import meso, paper\n"
            "a = meso.generate(seed=1, width_mm=6, height_mm=6, aggregate_area_fraction=0)\n"
            "bad = sorted(m for m in sys.modules if m == 'yade' or m.startswith('yade.') or m.startswith('swelldem.dem'))\n"
            "print('LOADED', bad, a.n_particles)\n")
    env = dict(os.environ, PYTHONPATH=os.path.join(REPO, "py"), SWELLDEM_BUILD_DIR=build_dir())
    p = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True, timeout=120, env=env)
    assert p.returncode == 0, p.stderr[-2000:]
    line = [ln for ln in p.stdout.splitlines() if ln.startswith("LOADED")][0]
    assert line.startswith("LOADED [] ") and int(line.split()[-1]) > 10, line


SCENE_SCRIPT = r"""
import sys, numpy as np, yade
from yade import wrapper as W
from swelldem import dem, meso
O = yade.Omega()
a = meso.generate(seed=2, width_mm=20, height_mm=20)          # concrete: aggregates, MORTAR/ITZ/AGG contacts
kinds = {"MORTAR": dem.contact_kind("MORTAR", swell_disp_inf=0.8e-6),
         "ITZ": dem.contact_kind("ITZ", b3="itz", swell_disp_inf=0.8e-6),
         "AGG": dem.contact_kind("AGG", young=60e9, swelling=True)}
solver = W.AdrLogTimeIntegrator(tStart=1, tEnd=10, stepsPerDecade=2, tolerance=1e-4, verbose=False)
O.tags["description"], O.tags["params"] = "batch job 7", "seed=2"   # as yade-batch sets them
tags_before = dict(O.tags)
ys = dem.to_yade(a, kinds, solver)
out = {"n_bodies": len(O.bodies), "n_real": sum(1 for i in O.interactions if i.isReal), "counts": ys.counts,
       "cohesive_after": ys.ip2.cohesive, "n_materials": len(O.materials), "n_aggregates": a.n_aggregates,
       "n_contacts": a.n_contacts, "tags_before": tags_before, "tags_after": dict(O.tags)}
out["body_agg_id"] = [O.bodies[i].material.aggregateId for i in range(a.n_particles)]
out["body_r"] = [O.bodies[i].shape.radius for i in range(a.n_particles)]
out["body_xy"] = [[O.bodies[i].state.pos[0], O.bodies[i].state.pos[1], O.bodies[i].state.pos[2]] for i in range(a.n_particles)]
out["blocked"] = sorted({O.bodies[i].state.blockedDOFs for i in range(a.n_particles)})
out["mat_ids_distinct"] = len({id(O.bodies[i].material) for i in range(a.n_particles) if a.aggregate_id[i] >= 0})
ph = [ys.interaction(c).phys for c in range(a.n_contacts)]
out["kind_id"] = [p.kindId for p in ph]
out["kind_name"] = [p.kindName for p in ph]
out["area"] = [p.area for p in ph]
out["length"] = [p.length for p in ph]
out["swell"] = [p.swellDispInf for p in ph]
# gel pockets: 10 % of the AGG contacts, seeded
chosen = dem.set_gel_pockets(ys, a, 0.1, 0.794e-6, seed=7)
out["chosen"] = chosen.tolist()
out["chosen_again"] = meso.choose_contacts(a, "AGG", 0.1, seed=7).tolist()
out["swell_after"] = [ys.interaction(c).phys.swellDispInf for c in range(a.n_contacts)]
# a few solver iterations: the assembly's contacts (some with a gap) stay real, nothing new appears
O.run(30, True)
out["real_after_run"] = sum(1 for c in range(a.n_contacts) if ys.interaction(c).isReal)
out["n_real_after_run"] = sum(1 for i in O.interactions if i.isReal)
# errors
errs = {}
def expect(name, fn):
    try:
        fn(); errs[name] = None
    except Exception as e:
        errs[name] = type(e).__name__ + ": " + str(e)
expect("missing_itz", lambda: dem.to_yade(a, {"MORTAR": kinds["MORTAR"], "AGG": kinds["AGG"]}, solver))
expect("bad_kind_id", lambda: dem.to_yade(a, {**kinds, "ITZ": dem.contact_kind("MORTAR")}, solver))
b = meso.generate(seed=2, width_mm=20, height_mm=20)
c0 = int(np.nonzero(b.kind == meso.MORTAR)[0][0]); b.kind[c0] = meso.AGG
expect("kind_mismatch", lambda: dem.to_yade(b, kinds, solver))
k2 = dict(kinds); k2["AGG"] = dem.contact_kind("AGG")        # swelling off
ys2 = dem.to_yade(a, k2, W.AdrLogTimeIntegrator(tStart=1, tEnd=10))
expect("gel_on_non_swelling", lambda: dem.set_gel_pockets(ys2, a, 0.1, 1e-6, seed=1))
out["errors"] = errs
dump(out)
"""


@pytest.fixture(scope="module")
def concrete_scene(tmp_path_factory):
    from conftest import YadeRun
    run = YadeRun(tmp_path_factory.mktemp("scene"))
    res = run(SCENE_SCRIPT, timeout=300)
    return res, meso.generate(seed=2, width_mm=20, height_mm=20)


def test_one_body_per_particle_at_the_assembly_positions(concrete_scene):
    res, a = concrete_scene
    assert res["n_bodies"] == a.n_particles
    np.testing.assert_array_equal(res["body_r"], a.r)
    xyz = np.array(res["body_xy"])
    np.testing.assert_array_equal(xyz[:, 0], a.x)
    np.testing.assert_array_equal(xyz[:, 1], a.y)
    assert np.all(xyz[:, 2] == 0)
    assert res["blocked"] == ["zXY"]


def test_scene_builder_keeps_the_batch_tags(concrete_scene):
    """The scene builder resets O but keeps O.tags: a yade-batch job's id, description and params."""
    res = concrete_scene[0]
    assert res["tags_after"]["description"] == "batch job 7" and res["tags_after"]["params"] == "seed=2"
    assert res["tags_after"] == res["tags_before"]


def test_one_material_per_aggregate(concrete_scene):
    res, a = concrete_scene
    assert a.n_aggregates >= 2 and set(a.aggregate_id) > {-1}
    np.testing.assert_array_equal(res["body_agg_id"], a.aggregate_id)
    assert res["n_materials"] == 1 + a.n_aggregates
    assert res["counts"]["n_aggregate_materials"] == a.n_aggregates


def test_one_real_interaction_per_contact_with_its_kind_and_facet_area(concrete_scene):
    res, a = concrete_scene
    assert res["n_real"] == a.n_contacts == res["counts"]["n_contacts"]
    np.testing.assert_array_equal(res["kind_id"], a.kind)
    assert [meso.KIND_NAMES[k] for k in a.kind] == res["kind_name"]
    assert all(res["counts"]["contacts_by_kind"][n] == int((a.kind == k).sum()) and (a.kind == k).sum() > 0
               for k, n in enumerate(meso.KIND_NAMES))
    np.testing.assert_array_equal(res["area"], a.facet_area_m2)             # set from the Laguerre facets, not the fallback
    np.testing.assert_allclose(res["length"], a.distance_m, rtol=0, atol=1e-12 * a.r.max())
    assert a.gap_m.max() > 1e-6 * a.r.max()                                  # some contacts start with a gap ...
    assert res["real_after_run"] == a.n_contacts                            # ... and stay real while the solver runs
    assert res["n_real_after_run"] == a.n_contacts                          # no stray contact appears at the start
    assert res["cohesive_after"] is False
    assert all(s == -1.0 for s in res["swell"])                             # no override unless asked


def test_gel_pockets_are_a_seeded_fraction_of_agg_contacts(concrete_scene):
    res, a = concrete_scene
    agg = np.nonzero(a.kind == meso.AGG)[0]
    chosen = np.array(res["chosen"])
    assert len(chosen) == round(0.1 * len(agg)) and set(chosen) <= set(agg)
    assert res["chosen_again"] == res["chosen"]
    sw = np.array(res["swell_after"])
    assert np.all(sw[chosen] == 0.794e-6)
    assert np.all(sw[np.setdiff1d(agg, chosen)] == 0.0)
    assert np.all(sw[a.kind != meso.AGG] == -1.0)
    other = meso.choose_contacts(a, "AGG", 0.1, seed=8)
    assert not np.array_equal(other, chosen)


def test_to_yade_errors(concrete_scene):
    e = concrete_scene[0]["errors"]
    assert "kinds['ITZ'] is missing" in e["missing_itz"]
    assert "kinds['ITZ'].kindId = 0" in e["bad_kind_id"]
    assert "is AGG in the assembly" in e["kind_mismatch"] and "'MORTAR'" in e["kind_mismatch"]
    assert "swelling is False" in e["gel_on_non_swelling"]


# Which kind a pair of particles makes, as ConcreteMat's and the Ip2's docstrings state it (written
# out here, not computed): platens first, then steel, then mortar / one aggregate / an interface.
PAIR_MATERIALS = {"mortar": {"aggregateId": -1}, "aggregate0": {"aggregateId": 0}, "aggregate1": {"aggregateId": 1},
                  "steel": {"steel": True}, "platen": {"platen": True}}
CONCRETE_PAIR_KIND = {("mortar", "mortar"): "MORTAR", ("mortar", "aggregate0"): "ITZ", ("mortar", "aggregate1"): "ITZ",
                      ("aggregate0", "aggregate0"): "AGG", ("aggregate0", "aggregate1"): "ITZ", ("aggregate1", "aggregate1"): "AGG"}


def expected_pair_kind(a, b):
    if "platen" in (a, b):
        return "PLATEN"
    if (a, b) == ("steel", "steel"):
        return "STEEL"
    if "steel" in (a, b):
        return "BOND"
    return CONCRETE_PAIR_KIND[(a, b)]


PAIR_SCRIPT = r"""
import itertools, yade
from yade import wrapper as W
from swelldem import dem, paper
mats = %r
names = list(mats)
pairs = list(itertools.combinations_with_replacement(names, 2))
materials = [W.ConcreteMat(young=30e9, poisson=0.2, density=2400, **mats[n]) for n in names]
R = 0.5e-3
x = [4 * R * k + d for k in range(len(pairs)) for d in (0.0, 2 * R)]
material_of = [names.index(n) for p in pairs for n in p]
slots = {name.lower(): dem.contact_kind(name) for name in (*paper.KIND_NAMES, *paper.STRUCTURE_KIND_IDS)}
ip2 = W.Ip2_ConcreteMat_ConcreteMat_SwellPhys(**slots)
ids, inters = dem.build_scene(x, [0.0] * len(x), [R] * len(x), materials, ip2, W.Law2_ScGeom_SwellPhys_AgingSwelling(), None,
                              material_of=material_of, contacts=[(2 * k, 2 * k + 1) for k in range(len(pairs))], collider=False)
dump([[a, b, I.phys.kindName, I.phys.kindId] for (a, b), I in zip(pairs, inters)])
""" % (PAIR_MATERIALS,)


def test_a_pair_gets_one_kind_from_the_ip2_and_from_the_generator(yade_run):
    made = yade_run(PAIR_SCRIPT, timeout=300)
    assert len(made) == 15
    ids = {**paper.KIND_IDS, **paper.STRUCTURE_KIND_IDS}
    for a, b, name, kind_id in made:
        want = expected_pair_kind(a, b)
        assert (name, kind_id) == (want, ids[want]), (a, b)
        if (a, b) in CONCRETE_PAIR_KIND:   # the generator knows concrete particles only
            agg = np.array([PAIR_MATERIALS[a]["aggregateId"], PAIR_MATERIALS[b]["aggregateId"]])
            assert meso.contact_kinds([0], [1], agg).tolist() == [ids[want]], (a, b)
            assert meso.contact_kinds([1], [0], agg).tolist() == [ids[want]], (b, a)


def test_without_the_plugin_is_a_clear_error(tmp_path):
    """Plain Debian yade (no overlay prefix): the plugin classes are missing."""
    script = tmp_path / "s.py"
    script.write_text("from swelldem import dem, meso\n"
                      "a = meso.generate(seed=1, width_mm=6, height_mm=6, aggregate_area_fraction=0)\n"
                      "try:\n    dem.to_yade(a, {}, None)\n"
                      "except dem.YadeUnavailableError as e:\n    print('CLEAR ERROR:', e)\n")
    env = {k: v for k, v in os.environ.items() if k != "YADE_PREFIX"}
    env.update(PYTHONPATH=os.path.join(REPO, "py"), SWELLDEM_BUILD_DIR=build_dir())
    p = subprocess.run(["/usr/bin/yade", "-n", "-x", str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
    assert "CLEAR ERROR:" in p.stdout and "plugin is not loaded" in p.stdout, p.stdout[-2000:] + p.stderr[-2000:]


# ------------------------------------------------------------------ Table 3.2, small

def test_table_3_2_small_free_swelling(tmp_path):
    out = tmp_path / "out"
    p = subprocess.run([LAUNCHER, "-n", "-x", TABLE_SCRIPT, "--size-mm", "8", "8", "--seed", "1", "--steps-per-decade", "5",
                        "--out", str(out)], capture_output=True, text=True, timeout=300,
                       env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir()})
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert (out / "strain.png").exists()
    res = json.loads((out / "results.json").read_text())
    for key in ("case", "n_particles", "r_mean_m", "d_inf_m", "eps_final_x", "eps_final_y", "eps_final", "paper_eps_final",
                "times_days", "eps_x", "eps_y", "adr_iterations", "wall_s"):
        assert key in res
    a = meso.generate(seed=1, width_mm=8, height_mm=8, aggregate_area_fraction=0)
    assert res["n_particles"] == a.n_particles and res["r_mean_m"] == pytest.approx(a.r.mean(), rel=1e-12)
    assert res["d_inf_m"] == pytest.approx(1000e-6 * 2 * a.r.mean(), rel=1e-12)
    eps, ex, ey = res["eps_final"], res["eps_final_x"], res["eps_final_y"]
    # The paper's Table 3.2: 1061e-6 with d_inf = 1000e-6 x 2 R_mean. Ours is below it: measured
    # -7.5 % here (981.1e-6, 8 x 8 mm seed 1, N = 5), -7.0 to -7.5 % over seeds 1-5 at 8 x 8 mm and
    # -7.1 to -7.3 % over seeds 1-3 at 20 x 20 mm (docs/mesostructure.md explains the gap: the
    # paper's figure needs contacts 7 % shorter than 2 R_mean). Tolerance: the largest measured
    # error, 7.5 %, plus a margin of 1 point (twice the seed-to-seed spread of 0.5 %).
    assert res["paper_eps_final"] == paper.TABLE_3_2_EPS_FINAL == 1061e-6
    assert abs(eps / paper.TABLE_3_2_EPS_FINAL - 1) <= 0.085, eps
    assert eps < paper.TABLE_3_2_EPS_FINAL
    # An affine expansion e in equilibrium gives e = d_inf / L_A, L_A the facet-area-weighted mean
    # contact length; the non-affine relaxation of the disordered network lowers it by 0-0.8 %.
    L_A = (a.facet_area_m2 * a.distance_m).sum() / a.facet_area_m2.sum()
    assert eps == pytest.approx(res["d_inf_m"] / L_A, rel=0.02)
    assert abs(ex - ey) <= 0.03 * eps      # isotropic within 3 % (measured 8 mm seeds 1-5: 0.5-2.1 %; 20 mm: 0.6 %)
    assert abs(res["eps_final_xy"]) <= 0.02 * eps
    # the curve follows eps_final x xi(t) (elastic, path independent), within the ADR tolerance
    tc, tl = 50.0, 100.0
    xi = lambda t: (1 - np.exp(-t / tc)) / (1 + np.exp(-(t - tl) / tc))
    t = np.array(res["times_days"])
    em = 0.5 * (np.array(res["eps_x"]) + np.array(res["eps_y"]))
    np.testing.assert_allclose(em, eps * (xi(t) - xi(t[0])) / (xi(t[-1]) - xi(t[0])), rtol=0, atol=0.01 * eps)


def test_compatible_swelling_gives_eps_inf_exactly(tmp_path):
    """d_inf = eps_inf x L on every contact is an affine expansion with no force: the whole chain
    (to_yade, per-contact overrides, ADR solver, strain measure) must return eps_inf x (xi(t_end) -
    xi(t_start)) to the ADR tolerance (1e-5 of the contact loads: ~1e-4 relative on the strain).
    The reference is computed here from the inputs given on the command line and the paper's ISR
    kinetics (Larive's sigmoid, tau_C = 50 d, tau_L = 100 d, to 3650 d), not read from the script."""
    eps_inf, t_start, t_end, tau_c, tau_l = 1000e-6, 0.01, 3650.0, 50.0, 100.0
    out = tmp_path / "out"
    p = subprocess.run([LAUNCHER, "-n", "-x", TABLE_SCRIPT, "--size-mm", "8", "8", "--seed", "2", "--steps-per-decade", "3",
                        "--case", "isr", "--eps-inf", repr(eps_inf), "--t-start", repr(t_start),
                        "--d-inf-rule", "contact-length", "--out", str(out)], capture_output=True, text=True, timeout=300,
                       env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir()})
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    res = json.loads((out / "results.json").read_text())
    xi = lambda t: (1 - math.exp(-t / tau_c)) / (1 + math.exp(-(t - tau_l) / tau_c))
    want = eps_inf * (xi(t_end) - xi(t_start))  # 999.976e-6: xi(0.01 d) = 2.4e-5
    assert res["times_days"][-1] == pytest.approx(t_end, rel=1e-12)
    for k in ("eps_final_x", "eps_final_y", "eps_final_side_x", "eps_final_side_y"):
        assert res[k] == pytest.approx(want, rel=2e-4), k
    assert abs(res["eps_final_xy"]) < 1e-4 * want
    assert res["final_fn_over_free_swelling_force"] < 1e-3


def test_compatible_swelling_of_a_3d_box_gives_eps_inf_exactly(tmp_path):
    """The same check on a box of spheres (table_3_2.py --dim 3): d_inf = eps_inf x L on every
    contact is an affine expansion without force, x, y and z alike."""
    eps_inf, t_start, t_end, tau_c, tau_l = 1000e-6, 0.01, 3650.0, 50.0, 100.0
    out = tmp_path / "out"
    p = subprocess.run([LAUNCHER, "-n", "-x", TABLE_SCRIPT, "--dim", "3", "--size-mm", "8", "8", "8", "--seed", "2",
                        "--steps-per-decade", "3", "--case", "isr", "--eps-inf", repr(eps_inf), "--t-start", repr(t_start),
                        "--d-inf-rule", "contact-length", "--out", str(out)], capture_output=True, text=True, timeout=600,
                       env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir()})
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    res = json.loads((out / "results.json").read_text())
    xi = lambda t: (1 - math.exp(-t / tau_c)) / (1 + math.exp(-(t - tau_l) / tau_c))
    want = eps_inf * (xi(t_end) - xi(t_start))
    assert res["dim"] == 3 and res["eps_final_side"] is None
    print("measured", [res[k] / want - 1 for k in ("eps_final_x", "eps_final_y", "eps_final_z")], res["final_fn_over_free_swelling_force"])
    for k in ("eps_final_x", "eps_final_y", "eps_final_z"):
        assert res[k] == pytest.approx(want, rel=2e-4), k
    assert abs(res["eps_final_xy"]) < 1e-4 * want
    assert res["final_fn_over_free_swelling_force"] < 1e-3
