# SPDX-License-Identifier: GPL-2.0-or-later
"""Every benchmark script that builds a swelling test's scene runs to its first table line at a tiny
size (real YADE, real plugin): the scenes come from swelldem.scenario.build, so a change of the
scenario's set-up cannot leave a benchmark dying at set-up (bench_scaling.py once passed tolerance 0
to the plugin, which refused it). Not timings: each is cut to a few iterations."""
import os
import subprocess
import sys

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
