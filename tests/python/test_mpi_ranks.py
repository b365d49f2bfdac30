# SPDX-License-Identifier: GPL-2.0-or-later
"""The implicit solver's PETSc solves on MPI ranks (`mpirun -n 2 scripts/yade-swelldem ...`): rank 0
holds the scene and hands each rank its rows, the rank above runs swelldem-solve-worker. Two ranks
end where one does (the closed form of a free swelling FCC lattice, and a loaded box whose platens
hold rows), and a run that would leave the ranks idle, or has no PETSc, is refused with a message."""
import json
import os
import subprocess

import pytest

from conftest import LAUNCHER, MPI_ENV, REPO, build_dir, mpirun
from test_solvers_3d import D_INF, FCC, R, RUN, larive


@pytest.fixture(scope="module")
def lattices(tmp_path_factory):
    from conftest import YadeRun
    out = {}
    for name in ("petsc-gamg", "petsc-mumps"):
        for ranks in (1, 2):
            run = YadeRun(tmp_path_factory.mktemp(f"{name}-{ranks}"))
            script = FCC.format(n=7, tol=1e-10, solver="ImplicitLogTimeSolver") + f"\nsolver.linearSolver = {name!r}\n" + RUN.format(hold="") \
                .replace('"iters": solver.totalIterations}', '"iters": solver.totalIterations, "pos": [list(b.state.pos) for b in O.bodies]}')
            out[name, ranks] = run(script, threads=1, ranks=ranks, timeout=300)
    return out


@pytest.mark.parametrize("name", ["petsc-gamg", "petsc-mumps"])
def test_two_ranks_swell_a_free_lattice_as_one_does(lattices, name):
    one, two = lattices[name, 1], lattices[name, 2]
    opening = D_INF * (larive(3650.0) - larive(1.0))
    # the closed form on two ranks: the lattice scales by 1 + d_inf dxi / (2 R)
    strain_err = max(abs((s - two["span0"]) / two["span0"] - opening / (2 * R)) for s in two["span"]) / (opening / (2 * R))
    apart = max(abs(a - b) for p, q in zip(two["pos"], one["pos"]) for a, b in zip(p, q)) / opening
    print(f"measured {name}: 2 ranks {strain_err:.1e} from the closed form, positions {apart:.1e} of an opening from 1 rank's; "
          f"Newton iterations {two['iters']} against {one['iters']}")
    # measured: 2.8e-12 (gamg) and 3.1e-13 (mumps) from the closed form; 1.1e-11 and 8.7e-13 of an
    # opening apart. Bounds: the implicit solver's 1e-9 (test_solvers_3d) and the 1e-8.
    assert strain_err < 1e-9 and apart < 1e-8


def _swelling_test(out, *args, ranks=1, env=None):
    e = {**os.environ, "SWELLDEM_BUILD_DIR": build_dir(), **MPI_ENV, **(env or {})}
    return subprocess.run(mpirun(ranks) + [LAUNCHER, "-j", "1", "-n", "-x", os.path.join(REPO, "scripts", "swelling_test.py"), "--dim", "3",
                                           "--size-mm", "8", "8", "8", "--aggregate-area-fraction", "0", *args, "--out", str(out)],
                          capture_output=True, text=True, timeout=600, env=e)


def test_a_loaded_box_on_two_ranks_ends_as_on_one(tmp_path):
    """8 mm mortar box, ISR viscoelastic without damage, under 1 MPa on its z faces, GAMG: the
    platens' held rows are padded into the blocks each rank owns. On 2 ranks the run keeps the
    default linear solver, auto, which takes GAMG there."""
    res = {}
    for ranks in (1, 2):
        chosen = ("--solver-param", "linearSolver='petsc-gamg'") if ranks == 1 else ()
        p = _swelling_test(tmp_path / str(ranks), "--scenario", "isr", "--behaviour", "viscoelastic", "--no-damage", "--steps-per-decade", "2",
                           "--boundary-z", "stress:-1e6", *chosen, ranks=ranks)
        assert p.returncode == 0, p.stderr[-3000:]
        res[ranks] = json.loads((tmp_path / str(ranks) / "results.json").read_text())
    a, b = res[1], res[2]
    assert a["status"] == b["status"] == "finished"
    assert b["solver_settings"]["linearSolver"] == "auto" and a["linear_solver"]["name"] == b["linear_solver"]["name"] == "petsc-gamg"
    err = {k: max(abs(x - y) for x, y in zip(a[k], b[k])) / max(abs(x) for x in a[k])
           for k in ("swelling_strain_x", "swelling_strain_y", "swelling_strain_z", "platen_disp_z_m")}
    print("measured: 2 ranks against 1, largest difference over the run relative to the largest value:", err)
    # measured: 6.2e-8 (x), 2.0e-8 (y), 2.7e-7 (z), 2.3e-7 (platen): steps settled at the positions'
    # round-off (ratio ~4e-8), reached through another partition of the smoother's blocks; bound
    # 2e-6, 7x.
    assert max(err.values()) < 2e-6


@pytest.mark.parametrize("args, env, message", [
    (("--solver-param", "linearSolver='cholmod'"), None,
     "ImplicitLogTimeSolver cannot start on 2 MPI ranks (mpirun): the ranks above 0 take part only in PETSc's linear solves; "
     "allowed under mpirun: ImplicitLogTimeSolver with linearSolver 'auto', 'petsc-gamg' or 'petsc-mumps'"),
    (("--solver", "adr"), None, "AdrLogTimeIntegrator cannot start on 2 MPI ranks (mpirun)"),
    (("--solver-param", "linearSolver='petsc-gamg'"), {"SWELLDEM_PETSC_MODULE": "/nonexistent/libswelldem_petsc.so"},
     "swelldem-solve-worker (MPI rank 1): PETSc is not available: the module /nonexistent/libswelldem_petsc.so could not be loaded"),
])
def test_a_run_that_cannot_use_the_ranks_is_refused_before_any_work(tmp_path, args, env, message):
    p = _swelling_test(tmp_path / "run", *args, ranks=2, env=env)
    assert p.returncode != 0 and message in p.stderr + p.stdout, (p.stdout[-2000:], p.stderr[-2000:])
    assert not (tmp_path / "run" / "results.json").exists()


def _run_in(tmp_path, name, script, ranks):
    """`script` run in its own folder tmp_path/name on `ranks` ranks (its own result.json, never an
    earlier run's)."""
    from conftest import YadeRun
    (tmp_path / name).mkdir()
    return YadeRun(tmp_path / name)(script, threads=1, ranks=ranks, timeout=300)


def _lattice_saved_after_a_step(state, solver_setting=""):
    """Script text: the free FCC lattice (5 layers) with the implicit solver, run on to step 2 and
    saved to `state`."""
    return FCC.format(n=5, tol=1e-10, solver="ImplicitLogTimeSolver") + solver_setting + f"""
while solver.step < 2:
    O.run(1, True)
O.save({str(state)!r})
"""


def test_a_loaded_run_that_would_leave_the_ranks_idle_is_refused(tmp_path):
    """A run started on one process, where auto takes CHOLMOD, saved after a step and loaded under
    mpirun -n 2: it keeps its linear solver (linearSolverUsed), which would leave rank 1 idle, and is
    refused at its first iteration after O.load, with the scene as loaded."""
    state = tmp_path / "state.yade"
    saved = _run_in(tmp_path, "one", _lattice_saved_after_a_step(state) + 'dump({"used": solver.linearSolverUsed, "step": solver.step})\n', 1)
    assert saved == {"used": "cholmod", "step": 2}
    go_on = f"""
O.load({str(state)!r})
solver = O.engines[-1]
before = (solver.step, solver.totalIterations)
try:
    O.run(5, True)
    error = ""
except Exception as e:
    error = str(e)
dump({{"error": error, "before": before, "after": (solver.step, solver.totalIterations)}})
"""
    res = _run_in(tmp_path, "two", go_on, 2)
    assert "ImplicitLogTimeSolver cannot go on on 2 MPI ranks (mpirun)" in res["error"], res
    assert "a run continued after O.load keeps the linear solver its first system took (ImplicitLogTimeSolver.linearSolverUsed)" in res["error"]
    assert res["after"] == res["before"], res


def test_a_gamg_run_saved_on_one_process_goes_on_on_two_ranks(tmp_path):
    """The free FCC lattice with petsc-gamg saved after a step on one process: loaded under mpirun
    -n 2 it goes on with its own solver, now sharing the solves, and ends where the unbroken run ends."""
    state = tmp_path / "state.yade"
    end = """
while not solver.finished:
    O.run(2000, True)
dump({"pos": [list(b.state.pos) for b in O.bodies], "used": solver.linearSolverUsed, "finished": solver.finished})
"""
    one = _run_in(tmp_path, "one", _lattice_saved_after_a_step(state, "\nsolver.linearSolver = 'petsc-gamg'\n") + end, 1)
    two = _run_in(tmp_path, "two", f"O.load({str(state)!r})\nsolver = O.engines[-1]\n" + end, 2)
    assert one["finished"] and two["finished"] and two["used"] == "petsc-gamg"
    opening = D_INF * (larive(3650.0) - larive(1.0))
    apart = max(abs(a - b) for p, q in zip(one["pos"], two["pos"]) for a, b in zip(p, q)) / opening
    print(f"measured: positions {apart:.1e} of an opening apart")
    # measured 7.8e-12 (the two ranks' smoother blocks differ); bound the issue's 1e-8, as above
    assert apart < 1e-8


def test_a_script_without_a_solver_ends_under_mpirun(yade_run):
    """The rank above waits for rank 0's commands from its start; rank 0 releases it at exit."""
    assert yade_run("dump({'ok': 1 + 1})", ranks=2, timeout=120) == {"ok": 2}


def test_a_mumps_factor_out_of_room_is_made_again(tmp_path):
    """8 mm mortar box on 2 ranks with MUMPS's workspace margin at 0 %: its estimate falls short
    (INFOG(1) = -9, which MUMPS prints at ICNTL(4) = 1), the factorization is made again with a wider
    margin, and the run ends where it ends with the default margin."""
    res = {}
    for name, options in (("tight", "-swelldem_mat_mumps_icntl_14 0 -swelldem_mat_mumps_icntl_4 1"), ("default", "")):
        p = _swelling_test(tmp_path / name, "--steps-per-decade", "2", "--solver-param", "linearSolver='petsc-mumps'", ranks=2,
                           env={"PETSC_OPTIONS": options})
        assert p.returncode == 0, p.stderr[-3000:]
        res[name] = (json.loads((tmp_path / name / "results.json").read_text()), p.stdout + p.stderr)
    (tight, log), (default, _) = res["tight"], res["default"]
    assert "INFOG(1)=" in log and " -9" in log.split("INFOG(1)=", 1)[1][:20], "the tight margin no longer runs out of room: pick a larger case"
    assert tight["status"] == default["status"] == "finished"
    err = max(abs(x / y - 1) for k in ("swelling_strain_x", "swelling_strain_y", "swelling_strain_z")
              for x, y in zip(tight[k][1:], default[k][1:]))
    print(f"measured: strains {err:.1e} apart")
    # two exact factors of the same matrices: measured 2.6e-13; bound 1e-9
    assert err < 1e-9
