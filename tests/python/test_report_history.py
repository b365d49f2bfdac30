# SPDX-License-Identifier: GPL-2.0-or-later
"""The solvers' unbalanced-force history (LogTimeSolver.historyEvery, historyIteration,
historyUnbalanced), the data of the paper's Figures 3.3-3.5 (left): on two free swelling discs
(conftest.swelling_pair), for both solvers, the records are exactly the iterations the setting
names (every historyEvery-th, each step's first and last; the set is built here from the per-step
iteration counts), the ratio at each step's last equals the solver's stepUnbalanced, the history
survives O.save / O.load, and a negative setting is refused."""
import pytest

from conftest import swelling_pair

SOLVERS = {
    "adr": "W.AdrLogTimeIntegrator(tStart=1.0, tEnd=3650.0, stepsPerDecade=3, tolerance=1e-6, verbose=False, historyEvery={every})",
    "implicit": "W.ImplicitLogTimeSolver(tStart=1.0, tEnd=3650.0, stepsPerDecade=3, verbose=False, historyEvery={every})",
}

RUN = r"""
while not solver.finished:
    O.run(1000, True)
O.save('pair.yade.gz')
O.load('pair.yade.gz')
loaded = [e for e in O.engines if type(e).__name__ == type(solver).__name__][0]
error = ""
try:
    loaded.historyEvery = -1
except Exception as e:
    error = str(e)
dump({"iteration": list(solver.historyIteration), "ratio": list(solver.historyUnbalanced),
      "step_iterations": list(solver.stepIterations), "step_unbalanced": list(solver.stepUnbalanced),
      "total": solver.totalIterations, "every": solver.historyEvery,
      "loaded_iteration": list(loaded.historyIteration), "loaded_ratio": list(loaded.historyUnbalanced), "error": error})
"""


def expected_records(step_iterations, every):
    """The cumulative iterations the history must hold: every `every`-th iteration, and the first
    and last iteration of every physical step."""
    want, end = set(), 0
    for n in step_iterations:
        start, end = end + 1, end + int(n)
        want |= {start, end}
    if every:
        want |= set(range(every, end + 1, every))
    return sorted(want)


@pytest.mark.parametrize("solver", list(SOLVERS))
def test_history_records_what_it_says(yade_run, solver):
    every = 3
    res = yade_run(swelling_pair(SOLVERS[solver].format(every=every)) + RUN, threads=1)
    steps = res["step_iterations"]
    assert len(steps) == 11  # 3 a decade from 1 to 3650 days: ceil(3 log10(3650)) steps
    assert sum(steps) == res["total"]
    assert res["every"] == every
    assert res["iteration"] == expected_records(steps, every)
    # the ratio recorded at each step's last iteration is the one the step converged with
    at = dict(zip(res["iteration"], res["ratio"]))
    ends = [sum(steps[:k + 1]) for k in range(len(steps))]
    assert [at[e] for e in ends] == res["step_unbalanced"]
    assert all(r >= 0 for r in res["ratio"])
    assert res["loaded_iteration"] == res["iteration"] and res["loaded_ratio"] == res["ratio"]
    assert "historyEvery = -1" in res["error"] and ">= 0" in res["error"], res["error"]


def test_history_off(yade_run):
    res = yade_run(swelling_pair(SOLVERS["adr"].format(every=0)) + RUN, threads=1)
    assert res["iteration"] == [] and res["ratio"] == []
    assert sum(res["step_iterations"]) == res["total"] > 0


def test_a_step_at_round_off_is_marked_with_its_limit(yade_run):
    """A step of the implicit solver that ends above its tolerance (1e-10) ends at the positions'
    round-off limit: it is marked (stepRoundOff), its limit recorded (stepRoundOffRatio), and its
    ratio is at or below that limit."""
    res = yade_run(swelling_pair(SOLVERS["implicit"].format(every=20)) + r"""
while not solver.finished:
    O.run(1000, True)
dump({"round_off": list(solver.stepRoundOff), "limit": list(solver.stepRoundOffRatio), "ratio": list(solver.stepUnbalanced),
      "tolerance": solver.tolerance})
""", threads=1)
    n = len(res["ratio"])
    assert n > 0 and len(res["limit"]) == n == len(res["round_off"]) and any(res["round_off"])
    for ro, limit, ratio in zip(res["round_off"], res["limit"], res["ratio"]):
        assert limit > 0
        if ro:
            assert res["tolerance"] < ratio <= limit
