# SPDX-License-Identifier: GPL-2.0-or-later
"""The solvers at the extremes: each run ends finite and in equilibrium, or stops with a clear
message; none writes NaN; what the ADR finishes the default (implicit) solver finishes too, by
itself handing a step it cannot settle to dynamic relaxation (recorded). Small specimens, real
YADE; the full table over three seeds is scripts/bench/bench_extremes.py (docs/performance.md
section 5)."""
import json
import math
import os
import subprocess

import pytest

from conftest import LAUNCHER, REPO, build_dir

SCRIPT = os.path.join(REPO, "scripts", "swelling_test.py")


def run(tmp_path, *args):
    out = tmp_path / "out"
    p = subprocess.run([LAUNCHER, "-n", "-x", SCRIPT, "--size-mm", "12", "12", "--steps-per-decade", "3", *args, "--out", str(out)],
                       capture_output=True, text=True, timeout=900, env={**os.environ, "SWELLDEM_BUILD_DIR": build_dir()})
    res = json.loads((out / "results.json").read_text()) if (out / "results.json").exists() else None
    return p, res


def finite(res):
    vals = res["swelling_strain_x"] + res["swelling_strain_y"] + res["unbalanced_ratio"]
    for k in ("MORTAR", "ITZ", "AGG"):
        vals += [v for v in res[f"fn_p05_kN_{k}"] + res[f"fn_p95_kN_{k}"] if v is not None]
    return all(math.isfinite(v) for v in vals)


def in_equilibrium(res, tol=1e-4):
    """Every step below the tolerance, or at the round-off limit of the positions (reported)."""
    return all(u <= tol * (1 + 1e-9) or r for u, r in zip(res["unbalanced_ratio"], res["step_at_round_off"]))


def assert_finished_in_equilibrium(p, res):
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert res["status"] == "finished"
    assert finite(res)
    assert in_equilibrium(res)


@pytest.mark.parametrize("name,args", [
    ("stiffness contrast 1e4", ("--behaviour", "elastic", "--no-damage", "--aggregate-young", "1e14")),
    ("zero swelling", ("--behaviour", "viscoelastic", "--eps-inf", "0")),
    ("start age 0.01 d", ("--behaviour", "viscoelastic", "--t-start", "0.01")),
    ("one step a decade", ("--behaviour", "viscoelastic", "--steps-per-decade", "1")),
    ("a single huge step", ("--behaviour", "viscoelastic", "--steps-per-decade", "0.25")),
])
def test_extreme_runs_end_finite_in_equilibrium(tmp_path, name, args):
    p, res = run(tmp_path, *args)
    assert_finished_in_equilibrium(p, res)
    if name == "zero swelling":
        assert max(abs(e) for e in res["swelling_strain_x"] + res["swelling_strain_y"]) < 1e-12
        assert all(res[f"broken_{k}"][-1] == 0 for k in ("MORTAR", "ITZ", "AGG"))
    if name == "a single huge step":
        assert len(res["times_days"]) == 1


@pytest.mark.parametrize("solver", ["implicit", "adr"])
@pytest.mark.parametrize("name,args", [
    ("swelling 100 times the paper's", ("--behaviour", "viscoelastic", "--eps-inf", "0.1")),
    ("all contacts broken", ("--behaviour", "elastic", "--strength-scale", "1e-9")),
])
def test_extreme_runs_with_an_equilibrium_finish(tmp_path, name, args, solver):
    """Both have an equilibrium at every step (a cracked, loose or hugely swollen free specimen
    carries no load it cannot balance), so either solver must reach it: status 'finished', every
    step below the tolerance, nothing but finite numbers. A run that stops here is a solver
    failure, not an acceptable end (measured, 12 mm, N = 3: all finish, every step at or below
    1e-4). Only the bonded contacts are counted broken. With strengths of 1e-9 times the paper's,
    no bonded contact is left in tension at a step's end: the ADR's transients pull every one
    through tension (all break); the implicit solver's steps are exact equilibria, where a contact
    that nothing loads any more (its discs free to move apart once their other contacts broke)
    carries next to no force and stays intact (3 of 318 mortar contacts at 12 mm, |Fn| <= 2.2e-8 N
    against strengths of 2.3e-6 to 3.0e-6 N), so every intact one ends at or below its strength."""
    p, res = run(tmp_path, *args, "--solver", solver)
    assert res is not None, "results.json is written from the first step on"
    assert finite(res), "no NaN is ever written"
    assert_finished_in_equilibrium(p, res)
    n = res["n_contacts_by_kind"]
    for k in n:
        assert all(b <= n[k] for b in res[f"broken_{k}"]), (k, "only the bonded contacts can break")
    if name == "all contacts broken":
        if solver == "adr":
            assert all(res[f"broken_{k}"][-1] == n[k] for k in n), {k: (res[f"broken_{k}"][-1], n[k]) for k in n}
        else:
            c = last_contacts(tmp_path / "out")
            intact = (c["bonded"] > 0) & (c["broken"] == 0)
            assert intact.sum() == sum(n[k] - res[f"broken_{k}"][-1] for k in n)
            assert (c["FnOverStrength"][intact] <= 1 + 1e-9).all(), c["FnOverStrength"][intact]
            assert intact.sum() < 0.05 * sum(n.values()), "near-zero strengths break nearly every contact"


def last_contacts(out):
    """Cell arrays of the last step's contacts file (the run writes the last step's VTK files)."""
    vtk = pytest.importorskip("vtk", reason="the contacts are read with VTK's reader: apt-get install python3-vtk9")
    from vtk.util.numpy_support import vtk_to_numpy
    path = sorted((out / "vtk").glob("contacts_*.vtp"))[-1]
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    cells = r.GetOutput().GetCellData()
    return {cells.GetArrayName(i): vtk_to_numpy(cells.GetArray(i)) for i in range(cells.GetNumberOfArrays())}


def fallback_recorded(res):
    """Every step the implicit solver handed to dynamic relaxation is in results.json with why."""
    fb = res["fallback_steps"]
    for f in fb:
        assert "Newton had not reached the tolerance" in f["why"] and f["relaxation_iterations"] >= 0 and f["wall_s"] >= 0, f
        assert f["t_days"] == res["times_days"][f["step"] - 1]
    return {f["step"] for f in fb}


def in_equilibrium_implicit(res):
    """Each step at 1e-10 (the implicit solver's tolerance) or at round-off, or, where it was handed
    to dynamic relaxation, at 1e-4 (the ADR's, the fallback's tolerance)."""
    fb = fallback_recorded(res)
    return all(u <= (1e-4 if i + 1 in fb else 1e-10) * (1 + 1e-9) or r
               for i, (u, r) in enumerate(zip(res["unbalanced_ratio"], res["step_at_round_off"])))


def intact_within_strength(out):
    """The contacts left intact carry at most their strength (from the last VTK contacts file)."""
    c = last_contacts(out)
    intact = (c["bonded"] > 0) & (c["broken"] == 0)
    assert (c["FnOverStrength"][intact] <= 1 + 1e-9).all(), c["FnOverStrength"][intact]
    return int(intact.sum())


# The cases of the issue in which the implicit solver stopped while the ADR finished (12 mm, damage
# on, seed 1 unless said; the one with stiff aggregates is cut at 200 d, past its hand-overs at
# 126-200 d). Measured (implicit): strengths x 1e-12: 1 step handed over (ratio 7.8e-5, 63
# contacts changing state at every Newton iteration), 7,883 iterations; ASR-coarse with every
# aggregate contact a gel pocket: 1 step; aggregate contacts x 1000, viscoelastic, seed 3: 7 steps
# over the whole run (Newton stalls at a ratio of 2e-5, the stiff contacts' round-off).
FINISH_CASES = [
    ("strengths x 1e-12", ("--steps-per-decade", "3", "--strength-scale", "1e-12"), "loose"),
    ("ASR-coarse, all gel pockets", ("--scenario", "asr-coarse", "--gel-fraction", "1", "--steps-per-decade", "10",
                                     "--strength-scale", "1e-9", "--t-end", "1000"), "loose"),
    ("aggregate x1000", ("--seed", "3", "--steps-per-decade", "10", "--aggregate-young", "6e13", "--t-end", "200"), "compare"),
]


@pytest.mark.parametrize("name,args,check", FINISH_CASES, ids=[c[0] for c in FINISH_CASES])
def test_the_default_solver_finishes_what_the_adr_finishes(tmp_path, name, args, check):
    """The ADR finishes each of these; the implicit solver, which stopped on them before it handed
    unsettled steps to dynamic relaxation, must finish them too, in equilibrium (1e-10, round-off,
    or 1e-4 on a handed-over step) with the hand-overs in results.json. Where nearly every contact
    breaks the specimen is a loose assembly with no unique strain: the check is then that the
    contacts left intact carry at most their strength (exact equilibria leave unloaded contacts
    intact where the ADR's transients pull them through tension) and that >= 95 % broke. Otherwise
    the strains agree with the ADR's within 2.1 % (its tolerance error, docs/performance.md
    section 1) plus the measured difference (aggregate x1000, seed 3, to 200 d: 0.2 %), bound 3 %."""
    adr_p, adr = run(tmp_path / "adr", *args, "--solver", "adr")
    assert adr_p.returncode == 0 and adr["status"] == "finished", adr_p.stderr[-2000:]
    p, res = run(tmp_path / "imp", *args, "--solver", "implicit")
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert res["status"] == "finished" and finite(res) and in_equilibrium_implicit(res)
    print("measured", name, "fallback steps", [(f["step"], f["relaxation_iterations"]) for f in res["fallback_steps"]],
          "strains", res["swelling_strain_x"][-1], adr["swelling_strain_x"][-1])
    if res["fallback_steps"]:
        assert "the step goes on by dynamic relaxation" in p.stdout and "finished by dynamic relaxation: fallback" in p.stdout
    n = res["n_contacts_by_kind"]
    if check == "loose":
        intact = intact_within_strength(tmp_path / "imp" / "out")
        assert intact <= 0.05 * sum(n.values())
    else:
        for axis in ("x", "y"):
            e, e0 = res[f"swelling_strain_{axis}"][-1], adr[f"swelling_strain_{axis}"][-1]
            assert abs(e - e0) <= 0.03 * abs(e0), (axis, e, e0)


def test_a_tolerance_cannot_be_met_by_a_step_that_has_not_moved(tmp_path):
    """Iteration 1 of a step measures its load before any move, at a ratio at or below about 1:
    with --tolerance 0.9 the implicit solver committed that state (1 iteration a step, strain
    exactly 0 against 903e-6, status 'finished'). It now meets a tolerance only after a Newton
    move. With damage a loose tolerance leaves the broken contacts' states unsettled; measured at
    12 mm: strains within 0.7 % of the default 1e-10 and 24 broken contacts against 25. Bounds:
    3 % and 3 contacts."""
    p, loose = run(tmp_path / "loose", "--tolerance", "0.9")
    assert p.returncode == 0 and loose["status"] == "finished"
    assert all(i >= 2 for i in loose["adr_iterations_per_step"]), "a step is judged after one move at least"
    _, ref = run(tmp_path / "ref")
    for axis in ("x", "y"):
        e, e0 = loose[f"swelling_strain_{axis}"][-1], ref[f"swelling_strain_{axis}"][-1]
        print("measured", axis, e, e0)
        assert abs(e - e0) <= 0.03 * abs(e0), (axis, e, e0)
    broken = [sum(r[f"broken_{k}"][-1] for k in r["n_contacts_by_kind"]) for r in (loose, ref)]
    assert abs(broken[0] - broken[1]) <= 3, broken
