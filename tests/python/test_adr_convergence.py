# SPDX-License-Identifier: GPL-2.0-or-later
"""The ADR reaches the equilibrium of an assembly whose Gershgorin mass bound is tight: two free
discs in contact, the smallest assembly with an equilibrium, swelling freely. Closed form (evaluated
here): no force, and the contact opens by d_inf (xi(t) - xi(t0)) with Larive's xi. At massSafety 1
(the bare bound) the contact mode sits on the stability limit and never decays: the same run stops
with 'no equilibrium', which is what the default's margin cures."""
import math

import pytest

from conftest import swelling_pair

ADR = "W.AdrLogTimeIntegrator(tStart=1.0, tEnd=3650.0, stepsPerDecade=5, tolerance=1e-6, verbose=False, maxIterations=3000{settings})"

# the run and what it records, after the scene of conftest.swelling_pair
RUN = r"""
error = ""
try:
    while not solver.finished:
        O.run(1000, True)
except Exception as e:
    error = str(e)
dump({"error": error, "steps": solver.nSteps, "iters": solver.totalIterations, "fn": O.interactions[a, b].phys.Fn,
      "gap": (O.bodies[b].state.pos - O.bodies[a].state.pos).norm() - 2 * R, "massSafety": solver.massSafety})
"""


def larive(t):
    return (1 - math.exp(-t / 50.0)) / (1 + math.exp(-(t - 100.0) / 50.0))


# Along an axis the bound is exact (the largest eigenvalue of the pair's stiffness is its row sum);
# along a diagonal it is loose by the |n_x| + |n_y| of the row sums.
@pytest.mark.parametrize("angle", [0.0, 0.4])
def test_two_free_discs_converge_adr(yade_run, angle):
    res = yade_run(swelling_pair(ADR.format(settings=""), angle) + RUN, threads=1)
    assert res["error"] == "", res["error"]
    assert res["steps"] == 18
    opening = 1e-6 * (larive(3650.0) - larive(1.0))
    kn = 30e9  # E A / L with A = 2R x 1 m and L = 2R
    # measured: |Fn| / (kn d_inf) and gap error 8.6e-10 (axis, 285 iterations a step), 3.9e-10 (diagonal, 21);
    # bounds 1e-6 (the tolerance) and 1e-5
    print("measured", abs(res["fn"]) / (kn * 1e-6), abs(res["gap"] - opening) / opening, res["iters"] / res["steps"])
    assert abs(res["fn"]) < 1e-6 * kn * 1e-6
    assert abs(res["gap"] - opening) < 1e-5 * opening


def test_two_free_discs_on_the_bare_mass_bound_never_settle(yade_run):
    res = yade_run(swelling_pair(ADR.format(settings=", massSafety=1.0")) + RUN, threads=1)
    assert "no equilibrium after maxIterations = 3000" in res["error"], res
