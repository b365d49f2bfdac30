# SPDX-License-Identifier: GPL-2.0-or-later
"""scripts/fit_kinetics.py recovers known parameters: a 20 x 20 mm ASR-fine specimen's expansion
curve made by the model with tau_c, tau_L and eps_inf set away from the paper's values (40 d,
120 d, 1500e-6 against 2500 d, 5000 d, 1000e-6), with 2 % noise (of its largest value, seeded), is
fitted back on two local Dask workers: each set value lies in the fit's stated 95 % interval, and
the residuals' RMS is the noise's. A two-stage curve, which one reaction's kinetics cannot follow,
is reported as a poor fit; curves that can be told bad before a run are refused before any."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO, build_dir

FIT = os.path.join(REPO, "scripts", "fit_kinetics.py")
LAUNCHER = os.path.join(REPO, "scripts", "yade-swelldem")
TRUE = {"tau_c": 40.0, "tau_L": 120.0, "eps_inf": 1.5e-3}
DAYS = [7, 14, 28, 56, 91, 120, 150, 180, 240, 300, 400, 550, 730, 1000]
NOISE = 0.02

pytest.importorskip("distributed", reason="Dask distributed (Debian python3-distributed) is installed by scripts/setup.sh")


def env():
    return {**os.environ, "SWELLDEM_BUILD_DIR": build_dir()}


def fit(data, out, *args, timeout=1500):
    return subprocess.run([sys.executable, FIT, "--data", str(data), "--scenario", "asr-fine", "--out", str(out), *args],
                          capture_output=True, text=True, timeout=timeout, env=env())


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    """The model's own curve at the set values (the solver stopping at the data's days), plus noise."""
    d = tmp_path_factory.mktemp("lab")
    extra = "[" + ",".join(f"{t:.1f}" for t in DAYS[:-1]) + "]"
    p = subprocess.run([LAUNCHER, "-n", "-j", "1", "-x", os.path.join(REPO, "scripts", "swelling_test.py"), "--scenario", "asr-fine",
                        "--behaviour", "viscoelastic", "--size-mm", "20", "20", "--seed", "1", "--steps-per-decade", "3",
                        "--t-end", str(DAYS[-1]), "--eps-inf", str(TRUE["eps_inf"]), "--kind-param", f"MORTAR.tauC={TRUE['tau_c']}",
                        "--kind-param", f"MORTAR.tauL={TRUE['tau_L']}", "--solver-param", f"extraTimes={extra}", "--out", str(d / "truth")],
                       capture_output=True, text=True, timeout=600, env=env())
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    res = json.loads((d / "truth" / "results.json").read_text())
    t = np.array(res["times_days"])
    expansion = 0.5 * (np.array(res["swelling_strain_x"]) + np.array(res["swelling_strain_y"]))
    y = np.array([expansion[np.argmin(abs(t - day))] for day in DAYS])
    assert all(min(abs(t - day)) < 1e-9 for day in DAYS)  # the run stopped at every day of the data
    noisy = y + NOISE * y.max() * np.random.default_rng(5).standard_normal(len(y))
    path = d / "lab.csv"
    path.write_text("day, expansion [1e-6]\n" + "".join(f"{a},{b * 1e6:.3f}\n" for a, b in zip(DAYS, noisy)))
    return path


def test_the_fit_recovers_the_set_values_within_its_uncertainty(lab, tmp_path):
    out = tmp_path / "fit"
    p = fit(lab, out, "--jobs", "2")
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    rec = json.loads((out / "fit.json").read_text())
    for name, true in TRUE.items():
        v = rec["values"][name]
        assert v["low95"] <= true <= v["high95"], (name, true, v)
        # an interval that says something: measured 95 % half-widths 3 % (tau_L), 5 % (eps_inf), 14 % (tau_c)
        assert v["high95"] / v["low95"] < 2.0, (name, v)
    rms = rec["fits"][0]["rms_relative"]
    assert 0.5 * NOISE < rms < 1.5 * NOISE, rms  # the residuals are the noise
    assert rec["quality"] == "good"
    rows = (out / "fit.csv").read_text().splitlines()
    data = [line.split(",", 1)[1] for line in lab.read_text().splitlines()[1:]]
    assert len(rows) == 1 + len(DAYS) and [float(r.split(",")[1]) for r in rows[1:]] == [float(d) for d in data]
    assert (out / "fit.png").stat().st_size > 20000 and "![fit](fit.png)" in (out / "fit.md").read_text()
    # a second call reuses every run
    p = fit(lab, out, "--jobs", "2", timeout=300)
    assert p.returncode == 0 and "runs on" not in p.stdout, p.stdout[-2000:]
    assert json.loads((out / "fit.json").read_text())["values"] == rec["values"]


@pytest.mark.parametrize("text,needle", [
    ("day, expansion [1e-6]\n0,0\n20,100\n10,200\n30,300\n", "swelldem: data days = '20 then 10' is out of range; allowed: strictly increasing days"),
    ("day, expansion [1e-6]\n-5,0\n20,100\n40,200\n60,300\n", "swelldem: data days = -5.0 is out of range; allowed: days >= 0"),
    ("day, expansion [1e-6]\n28,100\n", "swelldem: data points = 1 is out of range; allowed: at least 4"),
    ("day, expansion [1e-6]\n0,0\n50,1000\n100,600\n200,100\n", "falls by 90% after its maximum"),
    ("day, expansion\n0,0\n50,100\n100,200\n200,300\n", "swelldem: data header = 'expansion' is out of range"),
    ("day, expansion [%]\n0,0\n50,nan\n100,0.1\n200,0.1\n", "finite days and expansions"),
])
def test_curves_the_model_cannot_follow_are_refused_before_any_run(tmp_path, text, needle):
    data = tmp_path / "lab.csv"
    data.write_text(text)
    out = tmp_path / "fit"
    p = fit(data, out, timeout=120)
    assert p.returncode == 2 and p.stderr.startswith("fit_kinetics.py: ") and needle in p.stderr, p.stderr
    assert not out.exists()


def test_a_curve_the_model_cannot_follow_is_reported_as_a_poor_fit(tmp_path):
    """Two swelling stages (two Larive sigmoids, 700e-6 each, at 50 and 650 days): one reaction's
    kinetics cannot follow it, and the fit says so (measured RMS 20 % of the largest expansion)."""
    days = np.array([7, 14, 28, 56, 91, 120, 150, 180, 240, 300, 400, 500, 600, 700, 800, 1000.0])
    larive = lambda t, tc, tl: (1 - np.exp(-t / tc)) / (1 + np.exp(-(t - tl) / tc))  # noqa: E731
    y = 700 * larive(days, 15, 50) + 700 * larive(days, 30, 650)
    data = tmp_path / "two_stages.csv"
    data.write_text("day, expansion [1e-6]\n" + "".join(f"{a:g},{b:.2f}\n" for a, b in zip(days, y)))
    out = tmp_path / "fit"
    p = fit(data, out, "--size-mm", "16", "16", "--steps-per-decade", "2", "--jobs", "2")
    assert p.returncode == 1 and "fit_kinetics: poor fit (seeds [1])" in p.stdout, p.stdout[-2000:] + p.stderr[-2000:]
    rec = json.loads((out / "fit.json").read_text())
    assert rec["quality"] == "poor" and rec["fits"][0]["rms_relative"] > 0.1, rec["fits"][0]["rms_relative"]
    assert "Poor fit" in (out / "fit.md").read_text()
