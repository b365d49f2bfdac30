#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""The implicit solver's linear solvers against the cube's side: CHOLMOD's factor, PETSc's CG with
GAMG and MUMPS's factor, each on the same 3D swelling test (ISR, viscoelastic, damage on, 2 steps a
decade, aggregate fraction 0.2, seed 1), for its first physical steps or the whole run.

    SWELLDEM_BUILD_DIR=build /usr/bin/python3 scripts/bench/bench_linear_solvers.py [--sizes-mm 12 15 20 25 30]
        [--linear-solvers cholmod petsc-gamg petsc-mumps] [--steps 1] [--ranks 1 2] [--json out/bench/linear_solvers.json]

Each size and solver is one process of scripts/bench/bench_implicit_damage.py on one thread; it
reports its run time without the set-up, the factorizations or preconditioner set-ups and their
time, the Krylov solves and iterations, the x strain and its own peak resident size. At each size
the script prints every solver's run time over CHOLMOD's, both measured in this call, and the x
strain's difference from CHOLMOD's. --steps 0 runs the whole swelling test. --ranks 1 2 runs each
PETSc solver also under `mpirun -n 2` (rank 0 holds the scene, the other ranks take their rows of
each solve) and prints its run time over one rank's and their strains' difference; the peak is
rank 0's.
"""
import argparse
import os

import _common as C  # noqa: E402  (puts py/ on the path)

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bench_implicit_damage.py")


def one(size, linear, steps, seed, ranks=1):
    # Open MPI refuses root unless told (containers run as root)
    mpi = ["mpirun", "-n", str(ranks)] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) if ranks > 1 else []
    cmd = mpi + [C.LAUNCHER, "-n", "-j", "1", "-x", SCRIPT, "--dim", "3", "--size-mm", str(size), str(size), str(size),
           "--solver", "implicit", "--scenario", "isr", "--behaviour", "viscoelastic", "--seed", str(seed),
           "--steps-per-decade", "2", "--aggregate-area-fraction", "0.2", "--steps", str(steps),
           "--solver-param", f"linearSolver={linear!r}"]
    r, wall = C.run_result(cmd)
    r.update(size_mm=size, linear=linear, ranks=ranks, process_wall_s=round(wall, 1))
    return r


def describe(r):
    solves = r.get("krylov_solves") or 0
    per = f", {r['krylov_iterations'] / solves:.0f} Krylov iterations a solve ({solves} solves)" if solves else ""
    on = f" on {r['ranks']} MPI ranks" if r["ranks"] > 1 else ""
    return (f"{r['size_mm']:g} mm {r['linear']}{on}: {r['n_particles']} spheres, {r['status']}, run {r['wall_s']:.1f} s, "
            f"{r['factorizations']} set-ups in {r['factor_wall_s']:.1f} s{per}, peak {r['peak_mb']:.0f} MB, "
            f"factor entries {r['factor_nonzeros']:.3g}, strain x {r['strain_x']:.10e}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes-mm", type=float, nargs="+", default=[12.0, 15.0, 20.0])
    ap.add_argument("--linear-solvers", nargs="+", choices=["cholmod", "petsc-gamg", "petsc-mumps"],
                    default=["cholmod", "petsc-gamg", "petsc-mumps"])
    ap.add_argument("--steps", type=int, default=1, help="physical steps to run; 0: the whole swelling test")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1], help="MPI ranks of the PETSc solvers (1: no mpirun)")
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    rows = []
    for size in a.sizes_mm:
        here = {}
        for linear in a.linear_solvers:
            for ranks in (sorted(set(a.ranks) | {1}) if linear != "cholmod" else [1]):
                r = one(size, linear, a.steps, a.seed, ranks)
                rows.append(r)
                print(describe(r), flush=True)
                if ranks == 1:
                    here[linear] = r
                else:
                    one_rank = here[linear]
                    print(f"{size:g} mm: {linear} on {ranks} ranks / 1 rank run time {r['wall_s'] / one_rank['wall_s']:.2f}, "
                          f"strain x apart {abs(r['strain_x'] / one_rank['strain_x'] - 1):.1e}", flush=True)
        if "cholmod" in here:
            ref = here["cholmod"]
            for linear, r in here.items():
                if linear != "cholmod":
                    print(f"{size:g} mm: {linear} / cholmod run time {r['wall_s'] / ref['wall_s']:.2f}, peak {r['peak_mb'] / ref['peak_mb']:.2f}, "
                          f"strain x apart {abs(r['strain_x'] / ref['strain_x'] - 1):.1e}", flush=True)
    if a.json:
        C.write_json(a.json, {"rows": rows, "steps": a.steps})


main()
