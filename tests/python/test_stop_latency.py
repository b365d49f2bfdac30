# SPDX-License-Identifier: GPL-2.0-or-later
"""A stop signal reaches a running solve within one call of O.run: Python runs its handler only
between two calls, so swelldem.dem.run_to_end(seconds=...) sizes its calls by the measured time
of an iteration (a scenario asks for about a second) instead of a fixed count that, at seconds an
implicit iteration, would hold a SIGTERM for minutes. The chunking must not change the run."""
from conftest import swelling_pair

ADR = "W.AdrLogTimeIntegrator(tStart=1.0, tEnd=3650.0, stepsPerDecade=5, tolerance=1e-6, verbose=False)"

RUN = r"""
import os, signal, sys
MODE = sys.argv[1]
class Stop(Exception):
    pass
def stop(signum, frame):
    raise Stop()
signal.signal(signal.SIGTERM, stop)
# the signal is sent from inside iteration 7, in the thread O.run iterates in
O.engines = O.engines + [W.PyRunner(iterPeriod=1, command="os.kill(os.getpid(), signal.SIGTERM) if O.iter == 7 else None")]
stopped_at = None
try:
    if MODE == "seconds":
        dem.run_to_end(solver, chunk=1000, seconds=1e-9)
    else:
        dem.run_to_end(solver, chunk=1000)
except Stop:
    stopped_at = O.iter
dump({"stopped_at": stopped_at})
"""

PLAIN = r"""
import sys
MODE = sys.argv[1]
dem.run_to_end(solver, chunk=int(MODE))
dump({"fn": O.interactions[a, b].phys.Fn, "gap": (O.bodies[b].state.pos - O.bodies[a].state.pos).norm() - 2 * R,
      "iters": solver.totalIterations, "steps": solver.nSteps, "finished": solver.finished})
"""


def test_a_stop_signal_is_acted_on_within_one_call(yade_run):
    # calls sized to a nanosecond are one iteration each: the handler runs right after iteration 7
    assert yade_run(swelling_pair(ADR) + RUN, "seconds", threads=1)["stopped_at"] == 8
    # a fixed chunk of 1000 runs on to its end (or the solver's) before Python sees the signal
    assert yade_run(swelling_pair(ADR) + RUN, "fixed", threads=1)["stopped_at"] > 8


def test_the_chunking_does_not_change_the_run(yade_run):
    # calls of 97 iterations end inside the physical steps at other places than calls of 1000
    # (a call of O.run costs about 10 ms of its own, so the run is not made of one-iteration calls)
    short = yade_run(swelling_pair(ADR) + PLAIN, 97, threads=1)
    long = yade_run(swelling_pair(ADR) + PLAIN, 1000, threads=1)
    assert short["finished"] and short["iters"] > 1000 and short == long
