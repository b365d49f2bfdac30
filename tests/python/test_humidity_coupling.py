# SPDX-License-Identifier: GPL-2.0-or-later
"""The relative humidity of swelldem.moisture acting on the contacts (swelldem.dem.humidity): real
YADE runs of scripts' scenario against closed forms that the driver does not compute.

- h = 1 everywhere, with the moisture model on (faces exposed to 1): the saturated run bit for bit,
  with both solvers.
- A uniform h held constant (sealed faces): every swelling increment times f(h) = h^m, so a run
  without damage is linear in the loads and every strain is h^m times the saturated run's.
- Uniform drying of a mortar specimen whose contacts all shrink with k_sh: the imposed openings
  -k_sh L (h0 - h) are a uniform strain once h is uniform, the affine field meets it with zero
  forces, so the specimen's strain is -k_sh (h0 - h_end) and every force vanishes.
"""
import json
import os

import numpy as np
import pytest

from conftest import REPO, read_vtp

RUN = r"""
import sys, json
sys.path.insert(0, sys.argv[1])
from swelldem import scenario
out = {}
for spec in sys.argv[3:]:
    name, kw = spec.split('=', 1)
    kw = json.loads(kw)
    kw.setdefault('size_mm', (12, 12))
    kw['out'] = sys.argv[2] + '/' + name
    r = scenario.run(scenario.SwellingTest(**kw))
    out[name] = {k: r[k] for k in ('swelling_strain_x', 'swelling_strain_y', 'per_kind', 'iterations', 'humidity') if k in r}
    from yade import O
    fn = [abs(i.phys.Fn) for i in O.interactions if i.isReal and hasattr(i.phys, 'Fn')]
    out[name]['fn_max'] = max(fn) if fn else 0.0
    strain = [(O.bodies[i.id2].state.pos - O.bodies[i.id1].state.pos).norm() / i.phys.length - 1
              for i in O.interactions if i.isReal and hasattr(i.phys, 'length')]
    out[name]['contact_strain'] = [min(strain), max(strain)]
    out[name]['kn_l_max'] = max(i.phys.kn * i.phys.length for i in O.interactions if i.isReal and hasattr(i.phys, 'length'))
dump(out)
"""


def _spec(name, **kw):
    return f"{name}={json.dumps(kw)}"


def _run(yade_run, tmp_path, *specs, timeout=600):
    return yade_run(RUN, os.path.join(REPO, "py"), tmp_path, *specs, threads=1, timeout=timeout)


@pytest.mark.parametrize("solver", ["implicit", "adr"])
def test_saturated_moisture_model_is_the_saturated_run_bit_for_bit(yade_run, tmp_path, solver):
    common = dict(scenario="asr-fine", behaviour="viscoelastic", damage=True, solver=solver, steps_per_decade=4,
                  t_end_days=20000.0)
    res = _run(yade_run, tmp_path, _spec("plain", **common),
               _spec("wet", humidity_faces={"x-": 1.0, "y+": 1.0}, **common))
    plain, wet = res["plain"], res["wet"]
    assert "humidity" in wet and "humidity" not in plain
    assert wet["humidity"]["mean_h"]["specimen"][-1] == pytest.approx(1.0, abs=1e-12)
    for key in ("swelling_strain_x", "swelling_strain_y", "per_kind", "iterations"):
        assert wet[key] == plain[key], key
    assert sum(plain["per_kind"][k]["broken"][-1] for k in plain["per_kind"]) > 0  # damage ran: a test that can see a change


def test_uniform_humidity_is_the_saturated_swelling_times_h_to_the_m(yade_run, tmp_path):
    # A uniform h held constant (sealed) scales every swelling increment by f = h^m: the run is the
    # saturated one with eps_inf times f, which the reference runs without any moisture model. (Not
    # a plain ratio of strains: discs that come into touch make new, compression-only contacts, so
    # a free run is not linear in its load: 3e-4 relative at the end against the saturated run.)
    common = dict(scenario="asr-fine", behaviour="viscoelastic", damage=True, steps_per_decade=5, t_end_days=20000.0)
    eps = 1000e-6
    res = _run(yade_run, tmp_path, _spec("h09", humidity_initial=0.9, **common), _spec("ref09", eps_inf=eps * 0.9 ** 8, **common),
               _spec("h08m4", humidity_initial=0.8, humidity_exponent=4.0, **common), _spec("ref08m4", eps_inf=eps * 0.8 ** 4, **common))
    for name in ("09", "08m4"):
        got, ref = res["h" + name], res["ref" + name]
        assert abs(ref["swelling_strain_x"][-1]) > 1e-4
        # measured: the loads differ in the last bit ((d_inf dxi) f against (d_inf f) dxi); limit 1e-9
        for key in ("swelling_strain_x", "swelling_strain_y"):
            assert np.max(np.abs(np.subtract(got[key], ref[key]))) < 1e-9 * np.max(np.abs(ref[key])), (name, key)
        assert got["humidity"]["mean_h"]["specimen"][-1] == pytest.approx(0.9 if name == "09" else 0.8, abs=1e-12)


def test_uniform_drying_of_mortar_is_the_free_shrinkage(yade_run, tmp_path):
    k_sh, h_a = 2.0e-3, 0.6
    kw = dict(scenario="isr", eps_inf=0.0, behaviour="elastic", damage=False, aggregate_area_fraction=0.0, t_end_days=20000.0,
              steps_per_decade=5, humidity_faces={f: h_a for f in ("x-", "x+", "y-", "y+")}, shrinkage={"MORTAR": k_sh},
              kind_params={"MORTAR": {"behaviour": "elastic"}})  # a constant modulus: the end state is path-independent
    res = _run(yade_run, tmp_path, _spec("dry", **kw))["dry"]
    h_end = res["humidity"]["mean_h"]["MORTAR_contacts"][-1]
    assert h_end == pytest.approx(h_a, abs=1e-6)
    want = -k_sh * (1.0 - h_end)
    # every contact's centre distance changes by want x L (measured: 1.1e-5 of it at most, after
    # the drying's non-uniform path) and no contact carries a force (measured: 1e-6 of kn L want);
    # limits 10x
    lo, hi = res["contact_strain"]
    assert lo == pytest.approx(want, rel=1e-4) and hi == pytest.approx(want, rel=1e-4)
    assert res["fn_max"] < 1e-5 * res["kn_l_max"] * abs(want)
    # the specimen's strain, the skeleton's affine fit: measured 3.7e-4 relative above the closed
    # form (discs with two contacts in the fit that do not follow the affine field); limit 1e-3
    assert res["swelling_strain_x"][-1] == pytest.approx(want, rel=1e-3)
    assert res["swelling_strain_y"][-1] == pytest.approx(want, rel=1e-3)
    # on the way the faces dried first: the skin in tension (forces), shrinkage under way
    assert min(res["swelling_strain_x"]) < 0.5 * want


def test_drying_faces_outputs(yade_run, tmp_path):
    kw = dict(scenario="asr-fine", behaviour="viscoelastic", damage=True, steps_per_decade=4, t_end_days=20000.0,
              size_mm=(16, 12), humidity_faces={"x-": 0.5}, vtk_every=100)
    res = _run(yade_run, tmp_path, _spec("dry", **kw))["dry"]
    out = tmp_path / "dry"
    saved = json.load(open(out / "results.json"))
    hum = saved["humidity"]
    assert set(hum["mean_h"]) >= {"MORTAR_contacts", "ITZ_contacts", "AGG_contacts", "MORTAR_particles", "AGG_particles", "specimen"}
    assert hum["faces"] == {"x-": 0.5} and hum["balance_residual_max"] < 1e-12
    assert len(hum["times_days"]) == len(saved["times_days"]) + 1  # the planned times, tStart first
    data = np.load(out / "humidity.npz")
    assembly_x = np.load(out / "assembly.npz")["x"]
    h_mid = data["h"][np.argmin(np.abs(data["times_days"] - 100.0))]
    near, far = assembly_x < 3e-3, assembly_x > 13e-3
    assert h_mid[near].mean() < h_mid[far].mean() - 0.05  # dries from x- only
    for png in ("humidity_maps.png", "crack_map.png"):
        assert (out / png).stat().st_size > 10000
    _, cells, _, _ = read_vtp(sorted((out / "vtk").glob("particles_*.vtp"))[-1])
    assert np.allclose(np.sort(cells["h"]), np.sort(data["h"][-1]), atol=1e-6)  # float32 in the npz


@pytest.mark.parametrize("argv, message", [
    (["--humidity-face", "w+", "0.5"], "humidity_faces face = 'w+' is out of range; allowed: x-, x+, y-, y+"),
    (["--humidity-face", "z-", "0.5"], "humidity_faces face = 'z-'"),
    (["--humidity-face", "x-", "0"], "humidity_faces x- = 0.0 is out of range; allowed: 0 < humidity_faces x- <= 1"),
    (["--humidity-face", "x-", "1.2"], "humidity_faces x- = 1.2"),
    (["--humidity-face", "x-", "nan"], "humidity_faces x- = nan"),
    (["--humidity-initial", "1.5"], "humidity_initial = 1.5 is out of range; allowed: 0 < humidity_initial <= 1"),
    (["--humidity-initial", "0"], "humidity_initial = 0.0"),
    (["--humidity-face", "x-", "missing.csv"], "humidity_faces x- = 'missing.csv' is out of range"),
    (["--shrinkage", "STEEL=1e-3"], "shrinkage kind = 'STEEL'"),
    (["--shrinkage", "MORTAR=-1e-3"], "shrinkage MORTAR = -0.001"),
    (["--humidity-exponent", "-1"], "humidity_exponent = -1.0"),
    (["--humidity-face", "x-", "0.5", "--rebar-ratio", "0.01"], "rebar_ratio = 0.01 is out of range; allowed: 0 with a moisture model"),
])
def test_bad_humidity_input_is_refused_before_any_work(argv, message):
    import argparse
    from swelldem import scenario
    p = argparse.ArgumentParser()
    scenario.add_arguments(p)
    with pytest.raises(ValueError) as e:
        scenario.from_arguments(p.parse_args(argv)).validate()
    assert message in str(e.value)


@pytest.mark.parametrize("rows, message", [
    ("0, 0.9\n10, 0.8\n5, 0.7\n", "humidity_faces x- day (line 3) = 5.0 is out of range; allowed: day > 10, the previous row's (days strictly increasing) [day]"),
    ("0, 0.9\n10, 1.3\n", "humidity_faces x- h (line 2) = 1.3"),
    ("0, 0.9, 7\n", "humidity_faces x- line 1 = '0, 0.9, 7'"),
    ("# nothing\n", "a file with at least one row 'day, h'"),
])
def test_bad_humidity_history_is_refused(tmp_path, rows, message):
    from swelldem import scenario
    path = tmp_path / "rh.csv"
    path.write_text(rows)
    with pytest.raises(ValueError) as e:
        scenario.SwellingTest(humidity_faces={"x-": str(path)}).validate()
    assert message in str(e.value)


def test_humidity_history_file_is_read(tmp_path):
    from swelldem import scenario
    path = tmp_path / "rh.csv"
    path.write_text("# day, h\n0, 0.95\n\n100, 0.6  # dry spell\n1000,0.7\n")
    assert scenario.SwellingTest(humidity_faces={"y+": str(path)}).humidity_history() == {"y+": ([0.0, 100.0, 1000.0], [0.95, 0.6, 0.7])}


KILLED = r"""
import os, signal, sys, json
sys.path.insert(0, sys.argv[1])
from swelldem import scenario
kw = json.loads(sys.argv[3])
test = scenario.SwellingTest(save_state=True, out=sys.argv[2], **kw)
def kill():   # after the recorder has written step 9 and saved the state: killed as by SIGKILL
    if len(open(sys.argv[2] + "/curves.csv").read().splitlines()) - 1 == 9:
        os.kill(os.getpid(), signal.SIGKILL)
scenario.run(test, after_step=kill if sys.argv[4] == "kill" else None)
"""

RESUME = r"""
import sys
sys.path.insert(0, sys.argv[1])
from swelldem import scenario
scenario.run(scenario.resumed_test(sys.argv[2]), resume=True)
"""


def test_a_killed_drying_run_resumed_equals_the_uninterrupted_one(yade_run, tmp_path):
    """The driver sets the coming step's factors and openings after the state's load; the
    committed imposed openings come back with the state."""
    import signal
    kw = json.dumps(dict(scenario="isr", size_mm=[12.0, 12.0], steps_per_decade=5, humidity_faces={"x-": 0.5, "y+": 0.7}))
    py = os.path.join(REPO, "py")
    yade_run(KILLED, py, str(tmp_path / "ref"), kw, "run", threads=1)
    yade_run(KILLED, py, str(tmp_path / "run"), kw, "kill", threads=1, check=False)
    assert yade_run.proc.returncode == -signal.SIGKILL
    yade_run(RESUME, py, str(tmp_path / "run"), threads=1)
    ref, got = (json.load(open(tmp_path / n / "results.json")) for n in ("ref", "run"))
    assert got["status"] == "finished" and got["resumed"][0]["steps_done"] == 9
    assert ref["per_kind"]["ITZ"]["broken"][-1] > 0
    for key in ("times_days", "swelling_strain_x", "swelling_strain_y", "per_kind", "humidity"):
        assert got[key] == ref[key], key


def test_moisture_grid_keeps_every_physical_time_and_every_ambient_breakpoint():
    from swelldem.dem.humidity import substeps
    times = np.array([1.0, 10.0, 100.0, 1000.0])
    grid, index = substeps(times, 4, breakpoints=[0.5, 37.0, 38.0, 100.0, 2000.0])
    assert np.array_equal(grid[index], times)
    assert {37.0, 38.0} <= set(grid.tolist()) and 0.5 not in grid and 2000.0 not in grid
    assert np.all(np.diff(grid) > 0)
    # 4 a decade, each step one decade: 4 substeps, the second decade 2 more at the breakpoints
    assert np.diff(index).tolist() == [4, 6, 4]


def test_step_factor_is_f_integrated_over_the_swelling_of_the_step():
    from swelldem import paper
    from swelldem.dem.humidity import step_factor
    # h drops linearly in time from 1 to 0.6 over a step from 2000 to 8000 days of ASR kinetics,
    # f = h^8; the reference: the integral of f dxi / delta xi by fine quadrature (the closed-form xi)
    tc, tl, _ = paper.KINETICS["asr"]
    xi = lambda t: (1 - np.exp(-t / tc)) / (1 + np.exp(-(t - tl) / tc))  # noqa: E731
    h = lambda t: 1.0 - 0.4 * (t - 2000.0) / 6000.0  # noqa: E731
    fine = np.linspace(2000.0, 8000.0, 200001)
    ref = np.trapz(h(fine) ** 8 * np.gradient(xi(fine), fine), fine) / (xi(8000.0) - xi(2000.0))
    for n, limit in ((4, 0.106), (16, 6.6e-3), (64, 4.2e-4)):
        t = np.linspace(2000.0, 8000.0, n + 1)
        got = step_factor((h(t) ** 8)[:, None], xi(t))[0]
        # measured: 7.0e-2, 4.4e-3, 2.8e-4 relative (second order in the substeps); limits 1.5x
        assert abs(got / ref - 1) < limit, n
    assert step_factor(np.ones((5, 3)), [0.0, 0.1, 0.3, 0.35, 0.9]).tolist() == [1.0, 1.0, 1.0]
    # weights in time where xi does not move (no swelling in the step): the plain mean
    assert step_factor(np.array([[1.0], [0.5], [0.0]]), [0.2, 0.2, 0.2])[0] == pytest.approx(0.5)


def test_a_run_recorded_before_the_moisture_fields_reads_as_saturated():
    """A results.json written before the humidity fields existed is what that swelldem did: no
    moisture model. Comparisons of runs name the humidity settings only where they differ."""
    from swelldem import report, study
    old = {"config": {"scenario": "isr", "seed": 1}}
    new = {"config": {"scenario": "isr", "seed": 1, "humidity_faces": {}, "humidity_initial": 1.0, "shrinkage": {}}}
    dry = {"config": {"scenario": "isr", "seed": 1, "humidity_faces": {"x-": 0.5}}}
    assert report.differing_settings([old, new]) == []
    assert report.differing_settings([old, dry]) == ["humidity_faces"]
    assert study.differing(old["config"], {"humidity_faces": {}, "humidity_initial": 1.0}) == {}
    assert report.humidity_conditions(old["config"]) == [] and report.humidity_conditions(dry["config"]) == [
        "x- exposed to h 0.5", "h initial 1"]
