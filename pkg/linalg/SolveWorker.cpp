// SPDX-License-Identifier: GPL-2.0-or-later
// swelldem-solve-worker: what the ranks above 0 run under `mpirun -n P scripts/yade-swelldem ...`
// (the launcher starts it there instead of YADE): PETSc's share of the implicit solver's linear
// solves, on the commands of rank 0, which holds the scene. It opens the PETSc module as the
// plugin does, so that a machine without PETSc gets a message rather than the loader's failure.
#include "SparseSolver.hpp"
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

int main()
{
	try {
		return swelldem::linalg::runSolveWorker();
	} catch (const std::exception& e) {
		const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
		if (!rank) rank = std::getenv("PMI_RANK");
		std::fprintf(stderr, "swelldem-solve-worker (MPI rank %s): %s; under mpirun the implicit solver's linear solves need PETSc\n",
		             rank ? rank : "?", e.what());
		return 2;
	}
}
