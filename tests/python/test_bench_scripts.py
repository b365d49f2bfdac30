# SPDX-License-Identifier: GPL-2.0-or-later
"""The benchmark scripts run to their first table line at a tiny size (real YADE, real plugin; about
a minute in all). Those that build a swelling test's scene take it from swelldem.scenario.build, so
a change of the scenario's set-up cannot leave them dying at set-up (bench_scaling.py once passed
tolerance 0 to the plugin, which refused it). Not timings: each is cut to a few iterations.
Not here: bench_accuracy.py (at least 13 runs, about 2.5 min at 12 mm and 10 days; it runs through
scenario.run) and bench_extremes.py (36 runs of swelling_test.py; tests/python/test_extremes.py)."""
import os
import subprocess

import pytest

from conftest import LAUNCHER, REPO, build_dir

BENCH = os.path.join(REPO, "scripts", "bench")
PY = "/usr/bin/python3"


def run(cmd, cwd, timeout=300):
    env = dict(os.environ, SWELLDEM_BUILD_DIR=build_dir())
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env)
    assert p.returncode == 0, (p.returncode, p.stdout[-3000:], p.stderr[-3000:])
    return p.stdout


@pytest.mark.parametrize("name,args,first_line", [
    ("bench_scaling.py", ("--sizes-mm", "12", "--threads", "1", "--iters", "20", "--steps", "1", "--max-step-iters", "300",
                          "--calibration", "", "--out", "{tmp}/scaling.json"),
     "| size mm | discs | contacts | -j | wall ms/it |"),
    ("bench_order.py", ("--sizes-mm", "12", "--orders", "packing", "hilbert", "--repeats", "1", "--rounds", "1",
                        "--out", "{tmp}/order.json"),
     "| size mm | discs | numbering |"),
    ("bench_solvers.py", ("--sizes-mm", "12", "--out", "{tmp}/solvers"), "| case | discs | ADR wall s | implicit wall s |"),
    ("bench_adr_vs_yade.py", ("--n-discs", "200", "--repeat", "1", "--tolerances", "1e-2", "--ref-tol", "1e-5", "--err-targets", "1e-1",
                              "--out", "{tmp}/avy.json"), "tolerance |  ADR it | Newton it |"),
    ("bench_law_cost.py", ("--n-discs", "200", "--iters", "50", "--steps", "5", "--repeat", "1", "--chunks", "1", "--threads", "1",
                           "--out", "{tmp}/lc.json"), "variant |    j=1 us |  ratio |"),
    ("bench_mesostructure.py", ("--repeat", "1", "--size-mm", "12", "12", "--json", "{tmp}/m.json"), "per 100 x 100 mm specimen"),
    ("bench_laguerre3d.py", ("--sizes", "300", "--repeat", "1", "--json", "{tmp}/l3.json"), "| 256 | 5.43 |"),
    ("bench_packing3d.py", ("--sizes-mm", "4", "--json", "{tmp}/p3.json"), "| 4 | "),
    ("bench_meso3d.py", ("--sizes-mm", "4", "--json", "{tmp}/m3.json"), "| 4 | "),
    ("bench_linear_solvers.py", ("--sizes-mm", "12", "--linear-solvers", "cholmod", "petsc-gamg", "--json", "{tmp}/ls.json"),
     "12 mm: petsc-gamg / cholmod run time"),
])
def test_bench_driver_reaches_its_table(tmp_path, name, args, first_line):
    out = run([PY, os.path.join(BENCH, name)] + [a.format(tmp=tmp_path) for a in args], tmp_path)
    assert first_line in out, out[-3000:]


def test_bench_implicit_damage_reaches_its_result(tmp_path):
    """With a setting through --solver-param, as swelling_test.py takes it."""
    out = run([LAUNCHER, "-n", "-j", "1", "-x", os.path.join(BENCH, "bench_implicit_damage.py"), "--size-mm", "12", "12",
               "--steps-per-decade", "1", "--solver-param", "lowRankChanges=0"], tmp_path)
    line = next(ln for ln in out.splitlines() if ln.startswith("RESULT "))
    assert '"status": "finished"' in line and '"settings": {"lowRankChanges": "0"}' in line, line
