# SPDX-License-Identifier: GPL-2.0-or-later
"""Solver settings on the kind parameters' path (issue 25, item 3): every setting of either solver
reaches scripts/swelling_test.py through --solver-param NAME=VALUE, checked by the plugin; results.json
records them as run (solver_settings). Real YADE, 12 mm specimens, 3 steps a decade."""
import re

import pytest

from conftest import REPO, script_stderr
from test_scenarios import swelling_test


def header_settings(*classes):
    """The attribute names flagged swelldem_attr::Setting in pkg/yade/<class>.hpp."""
    names = set()
    for c in classes:
        with open(f"{REPO}/pkg/yade/{c}.hpp") as f:
            names |= set(re.findall(r"X\(\s*[\w:<>]+\s*,\s*(\w+)\s*,[^\n]*swelldem_attr::Setting", f.read()))
    return names


def test_swelldem_settings_are_the_c_plus_plus_settings(yade_run):
    """dem.solver_setting_names finds exactly the attributes the C++ headers flag Setting, for both
    solvers, and solver_defaults reads them from a fresh object (the class's defaults)."""
    got = yade_run("""
from swelldem import dem
dump({n: {"names": dem.solver_setting_names(n), "defaults": dem.solver_defaults(n)} for n in dem.SOLVERS})
""")
    assert set(got["adr"]["names"]) == header_settings("LogTimeSolver", "AdrLogTimeIntegrator")
    assert set(got["implicit"]["names"]) == header_settings("LogTimeSolver", "ImplicitLogTimeSolver")
    assert {"fallbackIterations", "fallbackTolerance"} <= set(got["implicit"]["names"])
    assert got["implicit"]["defaults"]["tolerance"] == 1e-10 and got["adr"]["defaults"]["tolerance"] == 1e-4


@pytest.fixture(scope="module")
def fallback_runs(tmp_path_factory):
    """A cracking 12 mm ISR viscoelastic run under the implicit solver, as is and with
    --solver-param fallbackIterations=3."""
    tmp = tmp_path_factory.mktemp("fallback")
    common = ("--scenario", "isr", "--behaviour", "viscoelastic", "--t-end", "300")
    ref, _ = swelling_test(tmp / "ref", *common)
    low, _ = swelling_test(tmp / "low", *common, "--solver-param", "fallbackIterations=3")
    return ref, low


def test_solver_param_changes_the_run(fallback_runs):
    """fallbackIterations=3 hands the cracking steps to dynamic relaxation (results.json
    fallback_steps), which the default (5000) does not; the setting is recorded as given and as run."""
    ref, low = fallback_runs
    assert sum(ref["per_kind"]["MORTAR"]["broken"][-1:] + ref["per_kind"]["ITZ"]["broken"][-1:]) > 0, "the run cracks"
    assert ref["fallback_steps"] == [] and len(low["fallback_steps"]) > 0, (ref["fallback_steps"], low["fallback_steps"])
    assert low["config"]["solver_params"] == {"fallbackIterations": 3}
    assert low["solver_settings"]["fallbackIterations"] == 3 and ref["solver_settings"]["fallbackIterations"] == 5000


def test_solver_settings_are_the_solvers_attributes(fallback_runs, yade_run):
    """results.json solver_settings: every setting of the solver's class, with its value as run:
    the class's defaults but for what the test sets (schedule, label-free) and what it overrides."""
    ref, low = fallback_runs
    defaults = yade_run("from swelldem import dem\ndump(dem.solver_defaults('implicit'))")
    assert set(ref["solver_settings"]) == header_settings("LogTimeSolver", "ImplicitLogTimeSolver")
    expected = dict(defaults, tStart=1.0, tEnd=300.0, stepsPerDecade=3.0)
    assert ref["solver_settings"] == expected
    assert low["solver_settings"] == dict(expected, fallbackIterations=3)
    assert ref["tolerance"] == ref["solver_settings"]["tolerance"] == defaults["tolerance"]


def test_solver_param_overrides_the_options_and_reaches_the_adr(tmp_path):
    """A setting of the ADR solver's class (and of LogTimeSolver) by --solver-param, over the
    dedicated option: stepsPerDecade=1 gives one step a decade whatever --steps-per-decade."""
    res, _ = swelling_test(tmp_path / "adr", "--solver", "adr", "--behaviour", "elastic", "--no-damage", "--t-end", "100",
                           "--solver-param", "stepsPerDecade=1", "--solver-param", "maxDamping=1.5")
    assert res["times_days"] == pytest.approx([10, 100])  # the step ends
    assert res["solver_settings"]["stepsPerDecade"] == 1 and res["solver_settings"]["maxDamping"] == 1.5
    assert res["solver_settings"]["tolerance"] == res["tolerance"]


@pytest.mark.parametrize("args,needle", [
    (("--solver-param", "fallbackIterationz=3"),
     "swelldem: solver_params name = 'fallbackIterationz' is not a setting of the implicit solver (ImplicitLogTimeSolver); "
     "allowed: autoFactorMemoryShare, breakOneAtATime, changingLimit, colliderLabel, colliderPeriod, divergenceRatio, extraTimes, fallbackIterations, "),
    (("--solver", "adr", "--solver-param", "fallbackIterations=3"),
     "swelldem: solver_params name = 'fallbackIterations' is not a setting of the adr solver (AdrLogTimeIntegrator); allowed: "),
    (("--solver-param", "totalIterations=3"), "'totalIterations' is not a setting of the implicit solver"),
    (("--solver-param", "fallbackIterations=-1"), "ImplicitLogTimeSolver.fallbackIterations = -1 is out of range; allowed: >= 0"),
    (("--solver-param", "gmresLimit=0"), "ImplicitLogTimeSolver.gmresLimit = 0 is out of range; allowed: 1 <= gmresLimit <= 1073741824"),
    (("--solver-param", "gmresLimit=2147483648"), "ImplicitLogTimeSolver.gmresLimit = 2147483648 is out of range; allowed: 1 <= gmresLimit <= 1073741824"),
    (("--solver-param", "newtonLimit=abc"), "solver_params = \"newtonLimit='abc'\" is out of range; allowed: values of each setting's type"),
    (("--solver-param", "fallbackIterations"), "solver_param = 'fallbackIterations' is out of range; allowed: NAME=VALUE"),
])
def test_bad_solver_param_is_one_line_before_work(tmp_path, args, needle):
    """An unknown name, a name of the other solver, a result, a value the plugin refuses, a value of
    the wrong type, a malformed option: one line on stderr naming it, exit status 2, nothing made."""
    _, p = swelling_test(tmp_path / "bad", *args, check=False)
    lines = script_stderr(p.stderr)
    assert p.returncode == 2 and len(lines) == 1, (p.returncode, p.stderr[-2000:])
    assert lines[0].startswith("swelling_test.py: ") and needle in lines[0], lines
    assert not (tmp_path / "bad").exists()
