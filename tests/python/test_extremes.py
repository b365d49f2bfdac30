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
        vals += [v for v in res["per_kind"][k]["fn_p05_kN"] + res["per_kind"][k]["fn_p95_kN"] if v is not None]
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
        assert all(res["per_kind"][k]["broken"][-1] == 0 for k in ("MORTAR", "ITZ", "AGG"))
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
    carries next to no force and stays intact (12 mm: 50 of 431 bonded contacts, |Fn| <= 3.8e-8 N,
    at most 0.01 of their strengths of 2.3e-6 to 3.0e-6 N; 6 with kinkPasses 0, whose moves cross
    the broken contacts' kinks without their complementarity and pull more through tension), so
    every intact one ends at or below its strength; bound 20 % of the bonded contacts."""
    p, res = run(tmp_path, *args, "--solver", solver)
    assert res is not None, "results.json is written from the first step on"
    assert finite(res), "no NaN is ever written"
    assert_finished_in_equilibrium(p, res)
    n = res["n_contacts_by_kind"]
    for k in n:
        assert all(b <= n[k] for b in res["per_kind"][k]["broken"]), (k, "only the bonded contacts can break")
    if name == "all contacts broken":
        if solver == "adr":
            assert all(res["per_kind"][k]["broken"][-1] == n[k] for k in n), {k: (res["per_kind"][k]["broken"][-1], n[k]) for k in n}
        else:
            c = last_contacts(tmp_path / "out")
            intact = (c["bonded"] > 0) & (c["broken"] == 0)
            assert intact.sum() == sum(n[k] - res["per_kind"][k]["broken"][-1] for k in n)
            assert (c["FnOverStrength"][intact] <= 1 + 1e-9).all(), c["FnOverStrength"][intact]
            assert intact.sum() < 0.20 * sum(n.values()), "near-zero strengths break nearly every contact"


def last_contacts(out):
    """Cell arrays of the last step's contacts file (the run writes the last step's VTK files)."""
    from conftest import read_vtp
    return read_vtp(sorted((out / "vtk").glob("contacts_*.vtp"))[-1])[1]



def test_a_stiff_aggregate_settles_as_a_linear_step(tmp_path):
    """Elastic without damage, every step is linear: Newton settles it with one solve and the passes
    that check it. Aggregate contacts 1e4 x stiffer: an aggregate turns as a whole inside the
    matrix, held by the matrix alone. The solver's shift of the rotations' diagonal is taken of each
    disc's own diagonal but at most of the median disc's; a shift of 1e-3 of every disc's own
    diagonal is, on the stiff discs, of the order of the matrix's hold on the aggregate, and Newton
    then converges by about 0.8 an iteration (measured, 11 steps: 13 to 1,617 iterations a step, the
    first steps accepted at ratios up to 3.6e-4 as round-off). Measured with the cap: 1 to 6
    iterations a step, ratios at or below 4.5e-5 (the first steps, at the stiff contacts' round-off);
    bounds 12 iterations and 1e-4, the ADR's default tolerance."""
    p, res = run(tmp_path, "--behaviour", "elastic", "--no-damage", "--aggregate-young", "1e14", "--solver", "implicit")
    assert_finished_in_equilibrium(p, res)
    assert max(res["iterations_per_step"]) <= 12, res["iterations_per_step"]
    assert max(res["unbalanced_ratio"]) <= 1e-4, res["unbalanced_ratio"]
