# SPDX-License-Identifier: GPL-2.0-or-later
"""scripts/loaded_expansion.py on a tiny box: the ASR expansion under a load is the reactive
strain less the inert companion's under the same load; without damage the model is linear but for
the contacts made under the load, so that difference is the free expansion (superposition), which
the study's own files must show; the load is the one asked for."""
import csv
import json
import os
import subprocess

import pytest

from conftest import REPO, build_dir

SCRIPT = os.path.join(REPO, "scripts", "loaded_expansion.py")


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("loaded")
    proc = subprocess.run(["/usr/bin/python3", SCRIPT, "--out", str(out), "--stresses-mpa", "0", "5", "--size-mm", "8", "8", "8",
                           "--aggregate-area-fraction", "0", "--steps-per-decade", "1", "--no-damage"],
                          capture_output=True, text=True, timeout=900, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    return out


def test_the_asr_expansion_under_load_is_the_free_one_without_damage(study):
    with open(study / "loaded_expansion.csv") as f:
        rows = list(csv.DictReader(f))
    last = {}
    for r in rows:
        last[r["stress_MPa"]] = r
    # the companions' strains, read from their own results: the subtraction the table reports
    reactive = json.load(open(study / "S5MPa_reactive" / "results.json"))
    inert = json.load(open(study / "S5MPa_inert" / "results.json"))
    free = json.load(open(study / "S0MPa_reactive" / "results.json"))
    assert reactive["config"]["t_start_days"] == inert["config"]["t_start_days"] == 28.0  # loaded at 28 days (the default)
    assert inert["config"]["eps_inf"] == 0 and reactive["config"]["boundary_z"] == inert["config"]["boundary_z"] == "stress:-5e+06"
    assert inert["platen_stress_z_Pa"][-1] == pytest.approx(-5e6, rel=1e-3)  # the load is applied (ADR at 1e-4)
    along = reactive["swelling_strain_z"][-1] - inert["swelling_strain_z"][-1]
    assert float(last["5"]["asr_along_1e-6"]) == pytest.approx(along * 1e6, abs=1e-3)
    assert inert["swelling_strain_z"][-1] < -3e-4  # the inert box shortens under the load: the subtraction matters
    ratios = {k: float(last["5"][f"asr_{k}_1e-6"]) / float(last["0"][f"asr_{k}_1e-6"]) for k in ("along", "across", "volume")}
    print("measured ratios to the free expansion at 5 MPa without damage:", ratios)
    # superposition: measured 0.95 (along), 1.03 (across), 1.002 (volume) with the ADR at 1e-4 and
    # one step a decade; the departures are the compression-only contacts the load closes. Bounds
    # 0.1 and 0.02 (2x and 10x)
    assert abs(ratios["along"] - 1) < 0.1 and abs(ratios["across"] - 1) < 0.1 and abs(ratios["volume"] - 1) < 0.02
    assert free["swelling_strain_volume"][-1] == pytest.approx(float(last["0"]["asr_volume_1e-6"]) * 1e-6, rel=1e-6)
    assert (study / "loaded_expansion.png").exists() and "| 5 |" in (study / "loaded_expansion.md").read_text()


def test_a_folder_of_other_settings_is_refused(study):
    proc = subprocess.run(["/usr/bin/python3", SCRIPT, "--out", str(study), "--stresses-mpa", "0", "5", "--size-mm", "8", "8", "8",
                           "--aggregate-area-fraction", "0", "--steps-per-decade", "1"],
                          capture_output=True, text=True, timeout=300, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 2 and "a new folder or one of a study with the same settings" in proc.stderr and "damage False (asked True)" in proc.stderr, proc.stderr


@pytest.mark.parametrize("scale", ["0", "-1", "nan"])
def test_a_bad_strength_scale_is_refused_before_any_work(tmp_path, scale):
    out = tmp_path / "loaded"
    proc = subprocess.run(["/usr/bin/python3", SCRIPT, "--out", str(out), "--strength-scale", scale],
                          capture_output=True, text=True, timeout=120, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 2, proc.stdout[-2000:] + proc.stderr[-2000:]
    assert f"strength_scale = {float(scale)!r} is out of range; allowed: 0 < strength_scale < inf" in proc.stderr, proc.stderr
    assert not out.exists() or not any(out.iterdir())  # no run started
