// SPDX-License-Identifier: GPL-2.0-or-later
// swelldem-solve-worker: what the ranks above 0 run under `mpirun -n P scripts/yade-swelldem ...`
// (the launcher starts it there instead of YADE): PETSc's share of the implicit solver's linear
// solves, on the commands of rank 0, which holds the scene.
extern "C" int swelldem_petsc_worker();

int main() { return swelldem_petsc_worker(); }
