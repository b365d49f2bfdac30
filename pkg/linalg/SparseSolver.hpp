// SPDX-License-Identifier: GPL-2.0-or-later
// The implicit solver's linear solves when they go to PETSc rather than CHOLMOD: conjugate gradients
// with algebraic multigrid (GAMG) or MUMPS's sparse Cholesky factor. The PETSc code lives in its own
// module, libswelldem_petsc.so, opened on first use, so that a scene that keeps CHOLMOD loads neither
// PETSc nor MPI, and a machine without PETSc runs every other setting. Plain C++, free of YADE.
#pragma once
#include <memory>
#include <string>
#include <vector>

namespace swelldem::linalg {

// A rank-one term u v^T of the operator over at most 12 equations (a contact's DOFs; eq -1: unused).
struct RankOneTerm {
	int    eq[12];
	double u[12], v[12];
};

struct SolveReport {
	int         iterations = 0;     // Krylov iterations (0 for a direct solve)
	bool        converged  = true;  // the Krylov method reached rtol
	double      residual   = 0;     // its final residual 2-norm, relative to |b|
	std::string reason;             // PETSc's converged reason, when not converged
	bool        atLimit    = false; // GMRES stopped at its gmresLimit
};

class SparseSolver {
public:
	virtual ~SparseSolver() = default;
	virtual const char* name() const = 0;
	virtual bool        iterative() const = 0;
	// The n equations' place in blocks of blockSize (a body's DOFs): equation e is row fullOf[e] of a
	// matrix of nFull rows, whose other rows (held DOFs) stay out of the solve. Algebraic multigrid
	// then aggregates bodies, not single DOFs. Without a call, every equation is its own block.
	virtual void setBlocks(int n, int blockSize, int nFull, const int* fullOf) = 0;
	// The current matrix K (n x n, symmetric): its lower triangle in compressed columns, with Eigen's
	// (and CHOLMOD's) layout. A call with the pattern of the last one only copies the values.
	virtual void setMatrix(int n, const int* colStart, const int* row, const double* value) = 0;
	// Vectors that K maps to small forces (count of them, n entries each, one after the other: the
	// rigid-body modes), which algebraic multigrid must represent on every level; a direct solver
	// ignores them. They are orthonormalised here.
	virtual void setNearNullSpace(int count, const double* modes) = 0;
	// The preconditioner (GAMG's hierarchy) or the factor (MUMPS), from the current matrix.
	virtual void setup() = 0;
	// x = A^-1 b. A direct solver: A is the matrix of the last setup and the terms are not taken
	// (the caller applies them with Woodbury's formula, as with CHOLMOD). An iterative one: A is the
	// current matrix plus the terms, to the relative residual rtol, preconditioned by the last
	// setup; conjugate gradients where A is symmetric, GMRES otherwise, which stops after gmresLimit
	// iterations with the least residual it reached.
	virtual SolveReport solve(const double* b, double* x, double rtol, const std::vector<RankOneTerm>& terms, bool symmetric, int gmresLimit) = 0;
};

// name "petsc-gamg" or "petsc-mumps" (ImplicitLogTimeSolver.linearSolver's). Throws std::runtime_error saying why it cannot (the module or PETSc
// missing, an unknown name). The module is looked for at SWELLDEM_PETSC_MODULE if that is set, else
// where the build put it.
std::unique_ptr<SparseSolver> openPetsc(const std::string& name);

// The MPI ranks this process runs among (mpirun's environment: Open MPI's or MPICH's), 1 outside
// mpirun. With more than one, rank 0 is YADE and the others only solve PETSc's linear systems.
int mpiRanks();

// What the MPI ranks above 0 run (swelldem-solve-worker): rank 0's commands, their share of each
// PETSc solve, until rank 0 quits; returns the exit status. Throws std::runtime_error saying why
// if PETSc cannot be opened.
int runSolveWorker();

// Why PETSc cannot be opened here ("" if it can), without opening a solver: for checks before a run.
std::string petscUnavailable();

} // namespace swelldem::linalg
