# SPDX-License-Identifier: GPL-2.0-or-later
"""Reinforcing bars (swelldem.dem.rebar): layout and carving in plain Python; with real YADE, the
swelling of reinforced specimens against the unreinforced one, the bar stress against the forces
of its STEEL contacts read from the scene, the yield report, and bad input."""
import csv
import json
import os
import subprocess

import numpy as np
import pytest

from conftest import LAUNCHER, REPO, build_dir, script_stderr
from swelldem import meso, options
from swelldem.dem import rebar

SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")


@pytest.fixture(scope="module")
def assembly():
    return meso.generate(seed=2, width_mm=16, height_mm=16)


def test_layout_gives_the_ratio_as_steel_area_over_the_section(assembly):
    lay = rebar.layout(assembly.width_m, assembly.height_m, 0.02, n_bars=2)
    assert lay.n_bars * lay.thickness_m / assembly.height_m == pytest.approx(0.02)
    assert lay.y_m == pytest.approx((assembly.height_m / 4, 3 * assembly.height_m / 4))
    n = round(assembly.width_m / (2 * lay.radius_m))
    assert 2 * n * lay.radius_m == pytest.approx(assembly.width_m)  # touching discs span the width
    assert 0.8 < lay.radius_m / assembly.r.mean() < 1.25


def test_carving_removes_exactly_the_discs_the_bar_overlaps(assembly):
    lay = rebar.layout(assembly.width_m, assembly.height_m, 0.01)
    carved = rebar.carve(assembly, lay)
    y = lay.y_m[0]
    overlapping = np.abs(assembly.y - y) < assembly.r + lay.radius_m
    assert carved.n_particles == assembly.n_particles - overlapping.sum()
    assert np.all(np.abs(carved.y - y) >= carved.r + lay.radius_m)
    # contacts renumbered: every kept contact joins the same two discs as before
    kept = np.flatnonzero(~overlapping)
    old = {tuple(sorted((int(i), int(j)))) for i, j in assembly.contacts if not (overlapping[i] or overlapping[j])}
    new = {tuple(sorted((int(kept[i]), int(kept[j])))) for i, j in carved.contacts}
    assert new == old


@pytest.mark.parametrize("kw,name", [(dict(ratio=0.2), "rebar_ratio"), (dict(ratio=-0.01), "rebar_ratio"),
                                     (dict(ratio=float("nan")), "rebar_ratio"), (dict(ratio=0.01, n_bars=0), "rebar_bars"),
                                     (dict(ratio=0.01, y_m=[0.0]), "rebar_y_m[0]"), (dict(ratio=0.01, y_m=[0.1]), "rebar_y_m[0]"),
                                     (dict(ratio=0.01, young=0.0), "rebar_young"), (dict(ratio=0.01, n_bars=6), "rebar_bars"),
                                     (dict(ratio=0.01, n_bars=2, y_m=[4e-3, 5e-3]), "rebar_y_m[1]")])
def test_bad_layout_named_with_its_value(assembly, kw, name):
    with pytest.raises(options.OptionError) as e:
        rebar.layout(assembly.width_m, assembly.height_m, **kw)
    assert f"swelldem: {name} = " in str(e.value) and "allowed" in str(e.value)


def test_the_layout_that_fits_is_decided_by_the_options_alone():
    """16 mm: bars of 0.4 mm discs need a cover of 2 Rmax = 0.96 mm to the sides and between them,
    h / (2 n) >= r + 0.96 mm, so 5 bars fit (1.6 mm >= 1.36 mm) and 6 do not (1.33 mm); the count
    and the allowed range are in the message, computed without a mesostructure."""
    lay = rebar.layout(16e-3, 16e-3, 0.01, n_bars=5)
    assert lay.radius_m == pytest.approx(0.4e-3) and lay.n_discs == 20
    assert min(lay.y_m) - lay.radius_m >= 2 * 0.48e-3 and np.min(np.diff(lay.y_m)) - 2 * lay.radius_m >= 2 * 0.48e-3
    with pytest.raises(options.OptionError, match=r"^swelldem: rebar_bars = 6 is out of range; allowed: 1 <= rebar_bars <= 5: "):
        rebar.layout(16e-3, 16e-3, 0.01, n_bars=6)
    # the SwellingTest's check, before any work, is the same
    from swelldem import scenario
    with pytest.raises(options.OptionError, match=r"rebar_bars = 6 is out of range; allowed: 1 <= rebar_bars <= 5"):
        scenario.SwellingTest(size_mm=(16, 16), rebar_ratio=0.01, rebar_bars=6).validate()


def run(tmp_path, name, *args):
    out = tmp_path / name
    proc = subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, "--scenario", "isr", "--behaviour", "elastic", "--no-damage",
                           "--size-mm", "16", "16", "--seed", "2", "--steps-per-decade", "2", "--solver", "implicit",
                           "--out", str(out), *args],
                          capture_output=True, text=True, timeout=900, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return json.loads((out / "results.json").read_text())


def test_bars_restrain_the_expansion_along_them_and_carry_tension(tmp_path):
    # the reference is the same carved specimen with a bar of next to no stiffness (rho 1e-5): the
    # carving itself changes the specimen (docs/structures.md)
    runs = {rho: run(tmp_path, f"rho{rho}", "--rebar-ratio", str(rho), "--rebar-yield-stress", "60e6") for rho in (1e-5, 0.005, 0.02)}
    ex = {rho: r["swelling_strain_x"][-1] for rho, r in runs.items()}
    ey = {rho: r["swelling_strain_y"][-1] for rho, r in runs.items()}
    assert ex[1e-5] > ex[0.005] > ex[0.02] > 0
    # across the bars the expansion grows a little (measured 476e-6 -> 504e-6 at 2 %): the restraint
    # along x sends some of it across, as an applied stress does
    assert ey[0.02] > ey[1e-5]
    for rho, r in runs.items():
        smax, smean = np.array(r["rebar_stress_max_Pa"]), np.array(r["rebar_stress_mean_Pa"])
        assert len(smax) == len(smean) == len(r["times_days"]) and smean[-1] > 0 and np.all(smax >= smean)
        with open(tmp_path / f"rho{rho}" / "curves.csv") as f:  # the bars' stress curves, in Pa, beside the strains
            head, *rows = list(csv.reader(f))
        assert [float(row[head.index("rebar_stress_max [Pa]")]) for row in rows] == list(smax)
        assert [float(row[head.index("rebar_stress_mean [Pa]")]) for row in rows] == list(smean)
        assert (tmp_path / f"rho{rho}" / "structure_stress.png").exists()  # the bars' stresses drawn
        # the mean stress is E_s times the bar's elongation over its length, which cannot much exceed
        # the free expansion of the concrete it is bonded to: the bar line's own elongation against
        # the specimen's affine fit, measured 1.04 times it for the softest bar (bound 1.15)
        assert smean[-1] < r["rebar"]["young_Pa"] * ex[1e-5] * 1.15
        # yield reported at the first step whose largest stress reaches f_y
        fy = r["rebar"]["yield_stress_Pa"]
        k = int(np.argmax(smax >= fy)) if np.any(smax >= fy) else None
        assert r["rebar"]["yield_day"] == (r["times_days"][k] if k is not None else None)
    assert runs[0.005]["rebar"]["yield_day"] is not None  # the thin bar reaches 60 MPa
    assert runs[0.02]["rebar_stress_mean_Pa"][-1] < runs[0.005]["rebar_stress_mean_Pa"][-1]


BAR_STRESS = r"""
import sys
sys.path.insert(0, {py!r})
from swelldem import scenario, paper
import numpy as np
t = scenario.SwellingTest(scenario="isr", behaviour="elastic", damage=False, size_mm=(16, 16), seed=2, steps_per_decade=2,
                          solver="implicit", rebar_ratio=0.01, temperature_c=38.0, out="run")
res = scenario.run(t)
ip2 = [e for e in O.engines if e.label == "iloop"][0].physDispatcher.functors[0]
steel = [i for i in O.interactions if i.isReal and i.phys.kindId == paper.STRUCTURE_KIND_IDS["STEEL"]]
dump({{"fn": [i.phys.Fn for i in steel], "area": [i.phys.area for i in steel], "reported": res["rebar_stress_max_Pa"][-1],
      "thickness": res["rebar"]["thickness_m"], "bond": res["rebar"]["n_bond_contacts"],
      "bond_seen": sum(1 for i in O.interactions if i.isReal and i.phys.kindId == paper.STRUCTURE_KIND_IDS["BOND"]),
      "temperatures": {{n: list(getattr(ip2, n).temperatures) for n in ("itz", "bond")}},
      "bar_discs": sum(1 for b in O.bodies if getattr(b.material, "steel", False))}})
"""


def test_bar_stress_is_the_bar_force_over_its_section(yade_run, tmp_path):
    r = yade_run(BAR_STRESS.format(py=os.path.join(REPO, "py")))
    # the ParaView file marks the bar's discs (steel = 1): as many as the bar spans the width with
    from conftest import read_vtp
    steel = read_vtp(sorted((tmp_path / "run" / "vtk").glob("particles_*.vtp"))[-1])[1]["steel"]
    assert steel.sum() == r["bar_discs"] > 0
    section = r["thickness"] * 1.0  # thickness of the model: the generator's default 1 m
    assert np.allclose(r["area"], section)
    assert r["reported"] == pytest.approx(max(r["fn"]) / section, rel=1e-12)
    assert r["bond"] > 0 and r["bond_seen"] == r["bond"]
    # the bond is at the concrete's temperature (--temperature-c 38: 311.15 K)
    assert r["temperatures"]["bond"] == r["temperatures"]["itz"] == [38.0 + 273.15]


@pytest.mark.parametrize("args,text", [(["--rebar-ratio", "0.5"], "rebar_ratio = 0.5"), (["--rebar-ratio", "nan"], "rebar_ratio = nan"),
                                       (["--rebar-ratio", "0.01", "--rebar-bars", "0"], "rebar_bars = 0"),
                                       # layouts that do not fit a 12 mm specimen: 20 bars overlap, 5 leave less than 2 Rmax of concrete
                                       (["--size-mm", "12", "12", "--rebar-ratio", "0.01", "--rebar-bars", "20"],
                                        "rebar_bars = 20 is out of range; allowed: 1 <= rebar_bars <= 4: "),
                                       (["--size-mm", "12", "12", "--rebar-ratio", "0.01", "--rebar-bars", "5"],
                                        "rebar_bars = 5 is out of range; allowed: 1 <= rebar_bars <= 4: ")])
def test_swelling_test_refuses_bad_rebar_before_any_work(tmp_path, args, text):
    """Refused with one line on stderr (parameter, value, allowed range) and exit status 2 before the
    mesostructure is made: no output folder is left."""
    out = tmp_path / "run"
    proc = subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *args, "--out", str(out)], capture_output=True, text=True,
                          timeout=300, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 2 and text in proc.stderr and not out.exists(), (proc.returncode, proc.stderr[-2000:])
    assert "Traceback" not in proc.stderr and len(script_stderr(proc.stderr)) == 1, proc.stderr
    assert "mesostructure" not in proc.stdout
