# SPDX-License-Identifier: GPL-2.0-or-later
"""scripts/prism_strength.py: the compressive test of a 3D prism by displacement control.

With the swelling off the model is positively homogeneous in the strengths: every tensile strength
x S and every imposed displacement x S multiply every force by S and leave the breaking sequence
as it was (linear elastic and creep laws, friction proportional to the normal force, an ADR test
on a ratio of forces). So a prism at strength scale 2 loaded by twice the strain step must carry
twice the stress of the same prism at scale 1 at every step, with the same broken contacts: the
reference is that theorem, not a number the code produced. Bad options stop before any work."""
import json
import os
import subprocess

import pytest

from conftest import LAUNCHER, build_dir

SCRIPT = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "scripts", "prism_strength.py")


def run(tmp_path, *args, timeout=600):
    return subprocess.run([LAUNCHER, "-j", "1", "-n", "-x", SCRIPT, *args], cwd=tmp_path, capture_output=True, text=True,
                          timeout=timeout, env=dict(os.environ, SWELLDEM_BUILD_DIR=build_dir()))


def test_the_strength_scales_with_the_contact_strengths(tmp_path):
    curves = {}
    for scale in (1, 2):
        out = tmp_path / f"s{scale}"
        proc = run(tmp_path, "--strength-scale", str(scale), "--size-mm", "4", "4", "8", "--aggregate-area-fraction", "0",
                   "--strain-step", f"{100e-6 * scale!r}", "--max-strain", f"{3e-3 * scale!r}", "--drop", "0.9", "--out", str(out))
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
        curves[scale] = json.loads((out / "strength.json").read_text())
    a, b = curves[1], curves[2]
    assert a["tensile_strength_Pa"]["MORTAR"] * 2 == pytest.approx(b["tensile_strength_Pa"]["MORTAR"])
    assert a["status"] == b["status"] == "past_peak" and not a["peak_lower_bound"] and not b["peak_lower_bound"]
    # the steps up to the first one at which either curve falls: past a peak the breaking sequence can
    # part on a near tie (measured: it did at the 5th step of this 4 x 4 x 8 mm mortar prism)
    n = min(len(a["stress_Pa"]), len(b["stress_Pa"]))
    last = next((i for i in range(1, n) if a["stress_Pa"][i] < a["stress_Pa"][i - 1] or b["stress_Pa"][i] < b["stress_Pa"][i - 1]), n)
    assert last >= 5  # at least four loaded steps compared
    assert sum(a["broken"][last - 1].values()) > 0  # contacts have broken within them
    for i in range(1, last):
        assert b["strain"][i] == pytest.approx(2 * a["strain"][i], rel=1e-9)
        assert b["stress_Pa"][i] == pytest.approx(2 * a["stress_Pa"][i], rel=0.01)  # the ADR's 1e-4 tolerance, with margin
        assert b["broken"][i] == a["broken"][i]
    assert a["stress_Pa"][1] > 0  # compression positive


@pytest.mark.parametrize("option, value, message", [
    ("--strength-scale", "0", "strength_scale = 0.0 is out of range; allowed: 0 < strength_scale < inf [-]"),
    ("--drop", "1", "drop = 1.0 is out of range; allowed: 0 < drop < 1 [-]"),
    ("--strain-step", "0.01", "strain_step = 0.01 is out of range; allowed: 0 < strain_step <= 0.001 [-]"),
    ("--step-iterations", "10", "step_iterations = 10 is out of range"),
])
def test_bad_options_are_refused_before_any_work(tmp_path, option, value, message):
    out = tmp_path / "out"
    proc = run(tmp_path, option, value, "--out", str(out), timeout=120)
    assert proc.returncode == 2 and message in proc.stderr, proc.stdout[-2000:] + proc.stderr[-2000:]
    assert not out.exists()
