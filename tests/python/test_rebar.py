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
                                        "rebar_bars = 5 is out of range; allowed: 1 <= rebar_bars <= 4: "),
                                       # the BOND kind exists only with bars; its name and id are not the user's
                                       (["--kind-param", "BOND.tensileStrength=1e6"],
                                        "kind_params kind = 'BOND' is out of range; allowed: MORTAR, ITZ, AGG, and BOND when rebar_ratio > 0"),
                                       (["--rebar-ratio", "0.01", "--kind-param", "BOND.kindId=1"], "BOND.kindId = 1 is out of range"),
                                       (["--rebar-ratio", "0.01", "--kind-param", "BOND.tensileStrength=-1"], "tensileStrength")])
def test_swelling_test_refuses_bad_rebar_before_any_work(tmp_path, args, text):
    """Refused with one line on stderr (parameter, value, allowed range) and exit status 2 before the
    mesostructure is made: no output folder is left."""
    out = tmp_path / "run"
    proc = subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *args, "--out", str(out)], capture_output=True, text=True,
                          timeout=300, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 2 and text in proc.stderr and not out.exists(), (proc.returncode, proc.stderr[-2000:])
    assert "Traceback" not in proc.stderr and len(script_stderr(proc.stderr)) == 1, proc.stderr
    assert "mesostructure" not in proc.stdout


def _vtk_steps(out):
    """The contacts' VTK files of a run, step after step: [(cell arrays)], read with VTK's reader."""
    import xml.etree.ElementTree as ET
    from conftest import read_vtp
    files = [d.get("file") for d in ET.parse(out / "vtk" / "contacts.pvd").getroot().findall("Collection/DataSet")]
    return [read_vtp(out / "vtk" / f)[1] for f in files]


def test_structure_kinds_in_results_tables_curves_and_crack_map(tmp_path):
    """A bar with a weak bond (BOND.tensileStrength 0.5 MPa against the ITZ's 2 MPa: it debonds)
    between x platens: PLATEN, STEEL and BOND have their own per-kind series, rows and
    curve columns, and the broken BOND contacts their own colour on the crack map. The counts and
    quantiles are checked against every contact's state in the ParaView files (VTK's reader)."""
    out = tmp_path / "rb"
    proc = subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, "--scenario", "isr", "--behaviour", "elastic",
                           "--size-mm", "16", "16", "--seed", "2", "--steps-per-decade", "2", "--rebar-ratio", "0.02",
                           "--kind-param", "BOND.tensileStrength=0.5e6", "--boundary-x", "fixed", "--vtk-every", "1", "--out", str(out)],
                          capture_output=True, text=True, timeout=900, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    res = json.loads((out / "results.json").read_text())
    steps = _vtk_steps(out)
    assert len(steps) == len(res["times_days"])
    assert list(res["per_kind"]) == ["MORTAR", "ITZ", "AGG", "PLATEN", "STEEL", "BOND"]
    # the platens' contacts are a wall's, which the ParaView files (disc to disc lines) do not hold
    assert res["n_contacts_by_kind"]["PLATEN"] > 0
    assert all(len(v) == len(res["times_days"]) for v in res["per_kind"]["PLATEN"].values())
    ids = {"STEEL": 4, "BOND": 5}  # the kindId of each, as the VTK files' field data names them
    for name, k in ids.items():
        first = steps[0]
        assert res["n_contacts_by_kind"][name] == int(((first["kindId"] == k) & (first["bonded"] == 1)).sum()) > 0
        for s, cells in enumerate(steps):
            sel = cells["kindId"] == k
            broken = int(((cells["broken"] == 1) & (cells["bonded"] == 1) & sel).sum())
            assert res["per_kind"][name]["broken"][s] == broken, (name, s)
            assert res["per_kind"][name]["born_broken"][s] == int(((cells["bonded"] == 0) & sel).sum())
            q05, q95 = np.quantile(cells["Fn"][sel], [0.05, 0.95]) / 1e3
            assert res["per_kind"][name]["fn_p05_kN"][s] == pytest.approx(q05, rel=1e-9, abs=1e-12)
            assert res["per_kind"][name]["fn_p95_kN"][s] == pytest.approx(q95, rel=1e-9, abs=1e-12)
    last = steps[-1]
    bond_broken = int(((last["kindId"] == 5) & (last["broken"] == 1) & (last["bonded"] == 1)).sum())
    assert bond_broken > 0  # the weak bond breaks
    # table.md and table.csv: a row per structure kind, the BOND row with the broken count of the VTK
    rows = {line.split("|")[1].strip(): line for line in (out / "table.md").read_text().splitlines() if line.startswith("| ")}
    n_bond = res["n_contacts_by_kind"]["BOND"]
    assert f"| {bond_broken} ({100 * bond_broken / n_bond:.1f}) |" in rows["BOND"]
    assert {"PLATEN", "STEEL"} <= set(rows)
    with open(out / "table.csv") as f:
        table = {r["kind"]: r for r in csv.DictReader(f)}
    assert int(table["BOND"]["broken"]) == bond_broken and int(table["BOND"]["n_contacts"]) == n_bond
    with open(out / "curves.csv") as f:
        head, *curve = list(csv.reader(f))
    assert [int(r[head.index("BOND broken [-]")]) for r in curve] == res["per_kind"]["BOND"]["broken"]
    # the crack map draws the broken bond facets in their own colour (darkorange), not the mortar's blue
    import matplotlib.image
    img = matplotlib.image.imread(str(out / "crack_map.png"))[..., :3]
    orange = np.all(np.abs(img - np.array([1.0, 140 / 255, 0.0])) < 0.03, axis=-1)
    assert orange.sum() > 200 * bond_broken / 10, orange.sum()
