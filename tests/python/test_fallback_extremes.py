# SPDX-License-Identifier: GPL-2.0-or-later
"""The default (implicit) solver finishes the runs in which it stopped while the ADR finished, each
run with both solvers, and a loose tolerance that must not be met by a step
that has not moved. 12 mm specimens, real YADE; the table over three seeds is
scripts/bench/bench_extremes.py (docs/performance.md section 5). Apart from test_extremes.py so
that the two files run on two workers."""
import pytest

from test_extremes import finite, last_contacts, run
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
# on, seed 1 unless said; the viscoelastic one with stiff aggregates is cut at 200 d, past its
# cracking steps at 126-200 d). Measured (implicit): strengths x 1e-12: 3,329 iterations, no step
# handed over (with kinkPasses 0: 7,883, 1 step handed over at a ratio of 7.8e-5, 63 contacts
# changing state at every Newton iteration); ASR-coarse with every aggregate contact a gel pocket:
# 1 step; aggregate contacts x 1000, viscoelastic, seed 3: 26,288 iterations (the ADR: 318,532),
# steps 21 to 24 handed over, strains 1.5 % and 0.3 % from the ADR's.
FINISH_CASES = [
    ("strengths x 1e-12", ("--steps-per-decade", "3", "--strength-scale", "1e-12"), "loose"),
    ("ASR-coarse, all gel pockets", ("--scenario", "asr-coarse", "--gel-fraction", "1", "--gel-pockets", "single", "--gel-displacement", "rule", "--steps-per-decade", "10",
                                     "--strength-scale", "1e-9", "--t-end", "1000"), "loose"),
    # A cracking stiff aggregate: its just-broken contacts (kn'' 1000 x the matrix's) sit on their
    # open / closed kink, and a Newton move that crosses it without the contacts' complementarity
    # (ImplicitLogTimeSolver.kinkPasses) overshoots a thousandfold; with kinkPasses 0 the step goes
    # to dynamic relaxation, which at this contrast does not settle step 22 within maxIterations.
    ("aggregate x1000", ("--seed", "3", "--steps-per-decade", "10", "--aggregate-young", "6e13", "--t-end", "200"), "compare"),
    # A seed of the stiff-aggregate elastic case that the ADR finishes (docs/performance.md, section 5).
    ("aggregate x1000 elastic", ("--seed", "5", "--behaviour", "elastic", "--steps-per-decade", "3", "--aggregate-young", "6e13"), "compare"),
]


@pytest.mark.parametrize("name,args,check", FINISH_CASES, ids=[c[0] for c in FINISH_CASES])
def test_the_default_solver_finishes_what_the_adr_finishes(tmp_path, name, args, check):
    """The ADR finishes each of these; the implicit solver, which stopped on them before it handed
    unsettled steps to dynamic relaxation (and, on the stiff aggregate's cracking steps, before it
    solved a move across broken contacts' kinks as their LCP), must finish them too, in equilibrium
    (1e-10, round-off, or 1e-4 on a handed-over step) with the hand-overs in results.json. Where nearly every contact
    breaks the specimen is a loose assembly with no unique strain: the check is then that the
    contacts left intact carry at most their strength (exact equilibria leave unloaded contacts
    intact where the ADR's transients pull them through tension) and that nearly all broke
    (measured: 13.2 % of the bonded contacts intact in the ASR-coarse case at 1000 d, 57 of 431,
    none above its strength; 18 with kinkPasses 0, whose moves cross the broken contacts' kinks
    without their complementarity: the loose assembly's end state follows the iteration path;
    bound 20 %). Otherwise the specimen's expansion agrees with the ADR's: its area
    strain within 5 % and each direction's within 12 %. In these damage runs two solvers
    reach different crack patterns from round-off onwards; what is robust is the expansion, while
    its split between x and y follows which crack opened first. Measured, aggregate x1000 elastic
    at seeds 5, 6, 10 and 12 (the seeds of 5 to 15 that the ADR finishes): area strain at most
    3.1 % from the ADR's, directions at most 9.2 % (seed 5, x), while the ADR's own x strain spans
    7.9 % over those seeds; x1000 viscoelastic, seed 3: 1.5 % (x) and 0.3 % (y)."""
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
        assert intact <= 0.20 * sum(n.values()), (intact, sum(n.values()))
    else:
        for axis, bound in (("area", 0.05), ("x", 0.12), ("y", 0.12)):
            e, e0 = res[f"swelling_strain_{axis}"][-1], adr[f"swelling_strain_{axis}"][-1]
            assert abs(e - e0) <= bound * abs(e0), (axis, e, e0)


def test_a_tolerance_cannot_be_met_by_a_step_that_has_not_moved(tmp_path):
    """Iteration 1 of a step measures its load before any move, at a ratio at or below about 1:
    with --tolerance 0.9 the implicit solver committed that state (1 iteration a step, strain
    exactly 0 against 903e-6, status 'finished'). It now meets a tolerance only after a Newton
    move. With damage a loose tolerance leaves the broken contacts' states unsettled; measured at
    12 mm: strains within 0.7 % of the default 1e-10 and 24 broken contacts against 25. Bounds:
    3 % and 3 contacts."""
    p, loose = run(tmp_path / "loose", "--tolerance", "0.9")
    assert p.returncode == 0 and loose["status"] == "finished"
    assert all(i >= 2 for i in loose["iterations_per_step"]), "a step is judged after one move at least"
    _, ref = run(tmp_path / "ref")
    for axis in ("x", "y"):
        e, e0 = loose[f"swelling_strain_{axis}"][-1], ref[f"swelling_strain_{axis}"][-1]
        print("measured", axis, e, e0)
        assert abs(e - e0) <= 0.03 * abs(e0), (axis, e, e0)
    broken = [sum(r["per_kind"][k]["broken"][-1] for k in r["n_contacts_by_kind"]) for r in (loose, ref)]
    assert abs(broken[0] - broken[1]) <= 3, broken
