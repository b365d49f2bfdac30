# SPDX-License-Identifier: GPL-2.0-or-later
"""Readings of the paper's open choices (swelldem.readings, scripts/readings_study.py) and the ADR's
breakInIterations, the break rule one of them runs."""
import csv
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO, build_dir

from swelldem import meso, paper, readings
from swelldem.meso import gel_pockets

BREAKS = r"""
import sys
sys.path.insert(0, sys.argv[1])
from swelldem import scenario
out = {}
for flag in (False, True):
    r = scenario.run(scenario.SwellingTest(scenario='asr-fine', behaviour='elastic', size_mm=(12, 12), steps_per_decade=5,
                                           solver='adr', solver_params={'breakInIterations': flag}, out=sys.argv[2] + f'/{flag}'))
    # at the end, read from the scene: no intact contact above its strength
    worst = max((i.phys.Fn / i.phys.fnMax for i in O.interactions if i.isReal and not i.phys.broken and i.phys.Fn > 0), default=0)
    out[str(flag)] = {'broken': {k: v['broken'][-1] for k, v in r['per_kind'].items()}, 'worst': worst,
                      'setting': r['solver_settings']['breakInIterations'], 'status': r['status']}
dump(out)
"""


def test_adr_breaks_in_iterations_break_transient_overloads(yade_run, tmp_path):
    """breakInIterations: contacts break in the ADR's transients as well, so the elastic ASR-fine
    specimen loses far more mortar contacts than breaking at equilibrium (measured at 12 mm: 46
    against 1 of 318); both end in an equilibrium with every intact contact within its strength,
    and results.json records the setting."""
    res = yade_run(BREAKS, os.path.join(REPO, "py"), tmp_path, threads=1, timeout=900)
    at_eq, in_it = res["False"], res["True"]
    assert at_eq["status"] == in_it["status"] == "finished"
    assert at_eq["setting"] is False and in_it["setting"] is True
    assert in_it["broken"]["MORTAR"] >= at_eq["broken"]["MORTAR"] + 20, (at_eq, in_it)
    assert at_eq["worst"] <= 1 + 1e-9 and in_it["worst"] <= 1 + 1e-9


def test_the_implicit_solver_refuses_break_in_iterations(tmp_path):
    out = tmp_path / "run"
    proc = subprocess.run([os.path.join(REPO, "scripts", "yade-swelldem"), "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"),
                           "--solver", "implicit", "--solver-param", "breakInIterations=True", "--out", str(out)],
                          capture_output=True, text=True, timeout=300, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))
    assert proc.returncode == 2, proc.stderr[-2000:]
    assert "breakInIterations" in proc.stderr
    assert not (out / "results.json").exists()


def _script(*args, timeout=1500):
    return subprocess.run([sys.executable, os.path.join(REPO, "scripts", "readings_study.py"), *map(str, args)],
                          capture_output=True, text=True, timeout=timeout, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))


def test_bounds_before_any_run(tmp_path):
    """--bounds-only: per reading the restrained force of the median pocket and the bound on the AGG
    5 % quantile, from the mesostructure alone; recomputed here with a plain loop over the pockets."""
    out = tmp_path / "b"
    proc = _script("--group", "asr-coarse", "--size-mm", 16, 16, "--seeds", 1, "--readings", "single", "single-aggregate-d",
                   "--out", out, "--bounds-only")
    assert proc.returncode == 0, proc.stderr[-2000:]
    text = (out / "bounds.md").read_text()
    assert not any(p.name.endswith("-s1") for p in out.iterdir())  # nothing run
    a = meso.generate(seed=1, width_mm=16, height_mm=16)
    d = 1000e-6 * 2 * a.r.mean()
    for reading, factor in (("single", 1.0), ("single-aggregate-d", 10.0)):
        chosen = gel_pockets.choose(a, "single", 0.1, 1)
        forces = [0.0] * int((a.kind == meso.AGG).sum())
        for n, c in enumerate(chosen):
            forces[n] = -paper.AGGREGATE_YOUNG * a.facet_area_m2[c] / a.distance_m[c] * d * factor
        row = [line for line in text.splitlines() if line.startswith(f"| {reading} |")][0].split("|")
        assert float(row[2]) == len(chosen)
        assert float(row[3].split("(")[0]) == pytest.approx(np.median(forces[:len(chosen)]) / 1e3, abs=0.051)
        assert float(row[4].split("(")[0]) == pytest.approx(np.quantile(forces, 0.05) / 1e3, abs=0.051)
    assert "| single-aggregate-d |" in text and text.count("| no |") == 1 and text.count("| yes |") == 1


def test_readings_table_from_the_runs(tmp_path):
    """Two elastic-damage readings at 12 mm on seeds 1 and 3: every run made, and readings.md /
    readings.csv give each run's kind rows as mean, min and max over the seeds, recomputed here from
    the runs' results.json, beside Table 3.6's values; a second call runs nothing."""
    out = tmp_path / "r"
    args = ("--group", "elastic-damage", "--size-mm", 12, 12, "--seeds", 1, 3, "--readings", "all-at-once", "most-overloaded-first",
            "--steps-per-decade", 5, "--jobs", 2, "--out", out)
    proc = _script(*args)
    assert proc.returncode == 0, proc.stderr[-3000:]
    rows = list(csv.DictReader(open(out / "readings.csv")))
    assert len(rows) == 2 * 2 * 3  # readings x runs (ISR, ASR-fine elastic with damage) x kinds
    for row in rows:
        case = (row["scenario"], row["behaviour"], row["damage"])
        res = [json.loads((out / readings.run_folder("elastic-damage", row["reading"], case, s) / "results.json").read_text()) for s in (1, 3)]
        broken = [100.0 * r["per_kind"][row["kind"]]["broken"][-1] / r["n_contacts_by_kind"][row["kind"]] for r in res]
        p05 = [r["per_kind"][row["kind"]]["fn_p05_kN"][-1] for r in res]
        assert float(row["broken_mean"]) == pytest.approx(np.mean(broken), rel=1e-12, abs=1e-12)
        assert float(row["broken_min"]) == pytest.approx(min(broken), rel=1e-12, abs=1e-12)
        assert float(row["p05_max"]) == pytest.approx(max(p05), rel=1e-12)
        assert float(row["broken_paper"]) == paper.TABLE_FORCES[case][row["kind"]]["broken_pct"]
        assert row["broken_ok"] == str(abs(np.mean(broken) - float(row["broken_paper"])) <= 10.0)
    md = (out / "readings.md").read_text()
    assert "| most-overloaded-first |" in md and "checks met" in md
    again = _script(*args)
    assert again.returncode == 0 and "kept" in again.stdout + again.stderr
