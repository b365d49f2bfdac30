// SPDX-License-Identifier: GPL-2.0-or-later
// libswelldem_petsc.so: SparseSolver over PETSc's C API (Debian's petsc-dev, real double, 32-bit
// indices). One process, PETSC_COMM_SELF.
#include "SparseSolver.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <petscksp.h>
#include <stdexcept>

namespace swelldem::linalg {
namespace {
	static_assert(sizeof(PetscInt) == sizeof(int), "swelldem expects PETSc with 32-bit indices (Debian's petsc-dev)");
	static_assert(std::is_same<PetscScalar, double>::value, "swelldem expects PETSc with real double scalars");

	void check(PetscErrorCode code, const char* what)
	{
		if (code == 0) return;
		const char* text = nullptr;
		PetscErrorMessage(code, &text, nullptr);
		throw std::runtime_error(std::string("PETSc failed in ") + what + ": " + (text ? text : "unknown error") + " (code "
		                         + std::to_string(int(code)) + ")");
	}

	// PETSc is initialised once a process, without its signal handlers (YADE's and swelldem's
	// SIGTERM handling stay in charge) and with its errors returned, not printed: each becomes an
	// exception here, and the solver's message. Its options (PETSC_OPTIONS, e.g.
	// -swelldem_pc_gamg_threshold 0.02) reach the solvers through the prefix swelldem_.
	void initialise()
	{
		PetscBool done = PETSC_FALSE;
		check(PetscInitialized(&done), "PetscInitialized");
		if (done) return;
		static char  arg0[] = "swelldem", arg1[] = "-no_signal_handler";
		static char* args[] = { arg0, arg1, nullptr };
		int          argc   = 2;
		char**       argv   = args;
		check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
		PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
	}

	struct ShellContext {
		Mat                             K = nullptr;
		const std::vector<RankOneTerm>* terms = nullptr;
		const std::vector<int>*         map   = nullptr; // equation -> row
	};

	// y = K x + sum u (v . x)
	PetscErrorCode shellMult(Mat A, Vec x, Vec y)
	{
		ShellContext* ctx = nullptr;
		PetscCall(MatShellGetContext(A, &ctx));
		PetscCall(MatMult(ctx->K, x, y));
		const PetscScalar* xv;
		PetscScalar*       yv;
		PetscCall(VecGetArrayRead(x, &xv));
		PetscCall(VecGetArray(y, &yv));
		const std::vector<int>& map = *ctx->map;
		for (const RankOneTerm& t : *ctx->terms) {
			double s = 0;
			for (int k = 0; k < 12; ++k)
				if (t.eq[k] >= 0) s += t.v[k] * xv[map[size_t(t.eq[k])]];
			for (int k = 0; k < 12; ++k)
				if (t.eq[k] >= 0) yv[map[size_t(t.eq[k])]] += t.u[k] * s;
		}
		PetscCall(VecRestoreArray(y, &yv));
		PetscCall(VecRestoreArrayRead(x, &xv));
		return 0;
	}

	class PetscSolver : public SparseSolver {
	public:
		explicit PetscSolver(bool gamg)
		    : gamg_(gamg)
		{
			initialise();
		}
		~PetscSolver() override
		{
			if (ksp_) KSPDestroy(&ksp_);
			if (shell_) MatDestroy(&shell_);
			if (op_) MatDestroy(&op_);
			if (pre_) MatDestroy(&pre_);
			if (b_) VecDestroy(&b_);
			if (x_) VecDestroy(&x_);
		}
		const char* name() const override { return gamg_ ? "petsc-gamg" : "petsc-mumps"; }
		bool        iterative() const override { return gamg_; }

		void setBlocks(int n, int blockSize, int nFull, const int* fullOf) override
		{
			blockAsked_ = blockSize, nFullAsked_ = nFull, mapAsked_.assign(fullOf, fullOf + n);
		}

		void setMatrix(int n, const int* colStart, const int* row, const double* value) override
		{
			const int nnz = colStart[n];
			if (n != n_ || std::vector<int>(colStart, colStart + n + 1) != lowerStart_ || std::vector<int>(row, row + nnz) != lowerRow_
			    || mapAsked_ != map_ || nFullAsked_ != nFull_)
				makePattern(n, colStart, row);
			// a held row's diagonal: the mean diagonal of its equations' kind (translation or
			// rotation: the block position), so that Jacobi smoothing treats it as its neighbours
			std::vector<double> diagSum(blockSize_, 0.0);
			std::vector<int>    diagCount(blockSize_, 0);
			for (int j = 0; j < n; ++j)
				if (colStart[j] < colStart[j + 1] && row[colStart[j]] == j) diagSum[fullRow(j) % blockSize_] += value[colStart[j]], ++diagCount[fullRow(j) % blockSize_];
			full_.resize(source_.size());
			for (size_t k = 0; k < source_.size(); ++k) {
				if (source_[k] >= 0) full_[k] = value[source_[k]];
				else {
					const int d = -1 - source_[k];
					full_[k]    = diagCount[d] > 0 ? diagSum[d] / diagCount[d] : 1.0;
				}
			}
			copyValues(op_);
		}

		void setNearNullSpace(int count, const double* modes) override
		{
			// modified Gram-Schmidt, twice; a mode that a held DOF set takes out entirely is dropped
			std::vector<std::vector<double>> q;
			for (int m = 0; m < count; ++m) {
				std::vector<double> v(size_t(nFull_), 0.0);
				for (int e = 0; e < n_; ++e)
					v[size_t(fullRow(e))] = modes[size_t(m) * n_ + e];
				const double        size = std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0));
				for (int pass = 0; pass < 2; ++pass)
					for (const auto& e : q) {
						const double d = std::inner_product(v.begin(), v.end(), e.begin(), 0.0);
						for (int i = 0; i < nFull_; ++i)
							v[i] -= d * e[i];
					}
				const double left = std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0));
				if (!(left > 1e-8 * size)) continue;
				for (double& x : v)
					x /= left;
				q.push_back(std::move(v));
			}
			nullModes_ = q;
			haveNull_  = true;
		}

		void setup() override
		{
			if (!pre_) throw std::runtime_error("PETSc solver set up before its matrix");
			copyValues(pre_);
			if (!ksp_) {
				check(KSPCreate(PETSC_COMM_SELF, &ksp_), "KSPCreate");
				check(KSPSetOptionsPrefix(ksp_, "swelldem_"), "KSPSetOptionsPrefix");
				PC pc;
				check(KSPGetPC(ksp_, &pc), "KSPGetPC");
				if (gamg_) {
					check(KSPSetType(ksp_, KSPCG), "KSPSetType");
					check(PCSetType(pc, PCGAMG), "PCSetType");
					// The levels smooth with the inverse of each body's 6 x 6 block (a sphere's
					// translations and rotations, whose stiffnesses differ by r^2) on the assembled
					// matrix, not the operator with its rank-one terms: 12 mm ISR cube, first step,
					// 64 CG iterations a solve against 153 with PETSc's point Jacobi on the operator.
					// PETSC_OPTIONS given with the prefix swelldem_ take precedence.
					PetscBool set = PETSC_FALSE;
					check(PetscOptionsHasName(nullptr, "swelldem_", "-mg_levels_pc_type", &set), "PetscOptionsHasName");
					if (!set) check(PetscOptionsSetValue(nullptr, "-swelldem_mg_levels_pc_type", "pbjacobi"), "PetscOptionsSetValue");
					// four smoothing sweeps a level instead of two: 20 mm cube, first step, 201 CG
					// iterations in 31 s against 355 in 61 s
					check(PetscOptionsHasName(nullptr, "swelldem_", "-mg_levels_ksp_max_it", &set), "PetscOptionsHasName");
					if (!set) check(PetscOptionsSetValue(nullptr, "-swelldem_mg_levels_ksp_max_it", "4"), "PetscOptionsSetValue");
				} else {
					check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
					check(PCSetType(pc, PCCHOLESKY), "PCSetType");
					check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
				}
				check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
				// after the user's options: the shell operator (its rank-one terms) has no entries a
				// smoother could read, so the preconditioner works on the assembled matrix whatever
				// PETSC_OPTIONS say (PETSc's own SOR on the shell ends the process)
				if (gamg_) check(PCSetUseAmat(pc, PETSC_FALSE), "PCSetUseAmat");
				check(KSPGetType(ksp_, &chosenType_), "KSPGetType");
			}
			if (gamg_ && haveNull_) {
				std::vector<Vec> vecs(nullModes_.size());
				for (size_t m = 0; m < nullModes_.size(); ++m) {
					check(VecCreateSeq(PETSC_COMM_SELF, nFull_, &vecs[m]), "VecCreateSeq");
					PetscScalar* a;
					check(VecGetArray(vecs[m], &a), "VecGetArray");
					std::copy(nullModes_[m].begin(), nullModes_[m].end(), a);
					check(VecRestoreArray(vecs[m], &a), "VecRestoreArray");
				}
				MatNullSpace nsp;
				check(MatNullSpaceCreate(PETSC_COMM_SELF, PETSC_FALSE, PetscInt(vecs.size()), vecs.data(), &nsp), "MatNullSpaceCreate");
				check(MatSetNearNullSpace(pre_, nsp), "MatSetNearNullSpace");
				check(MatNullSpaceDestroy(&nsp), "MatNullSpaceDestroy");
				for (Vec& v : vecs)
					VecDestroy(&v);
				haveNull_ = false;
			}
			check(KSPSetReusePreconditioner(ksp_, PETSC_FALSE), "KSPSetReusePreconditioner");
			check(KSPSetOperators(ksp_, gamg_ ? shell_ : pre_, pre_), "KSPSetOperators");
			check(KSPSetUp(ksp_), "KSPSetUp");
			check(KSPSetReusePreconditioner(ksp_, PETSC_TRUE), "KSPSetReusePreconditioner");
		}

		SolveReport solve(const double* b, double* x, double rtol, const std::vector<RankOneTerm>& terms, bool symmetric) override
		{
			if (!ksp_) throw std::runtime_error("PETSc solve before its setup");
			SolveReport report;
			context_.terms = &terms;
			if (gamg_) {
				// The terms' sliding contacts make A unsymmetric: GMRES, with the preconditioner on the
				// right so that the residual it measures is A's own; CG (the unpreconditioned residual) otherwise.
				const bool cg = symmetric || terms.empty();
				if (chosenType_ && (std::strcmp(chosenType_, KSPCG) == 0 || std::strcmp(chosenType_, KSPGMRES) == 0)) {
					check(KSPSetType(ksp_, cg ? KSPCG : KSPGMRES), "KSPSetType");
					if (!cg) check(KSPGMRESSetRestart(ksp_, 100), "KSPGMRESSetRestart");
					check(KSPSetPCSide(ksp_, cg ? PC_LEFT : PC_RIGHT), "KSPSetPCSide");
					check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
				}
				check(KSPSetTolerances(ksp_, rtol, 0.0, PETSC_DEFAULT, 5000), "KSPSetTolerances");
			}
			PetscScalar* a;
			check(VecGetArray(b_, &a), "VecGetArray");
			std::fill(a, a + nFull_, 0.0);
			for (int e = 0; e < n_; ++e)
				a[fullRow(e)] = b[e];
			check(VecRestoreArray(b_, &a), "VecRestoreArray");
			context_.map = &map_;
			check(KSPSolve(ksp_, b_, x_), "KSPSolve");
			const PetscScalar* xv;
			check(VecGetArrayRead(x_, &xv), "VecGetArrayRead");
			for (int e = 0; e < n_; ++e)
				x[e] = xv[fullRow(e)];
			check(VecRestoreArrayRead(x_, &xv), "VecRestoreArrayRead");
			PetscInt           its = 0;
			KSPConvergedReason why;
			check(KSPGetIterationNumber(ksp_, &its), "KSPGetIterationNumber");
			check(KSPGetConvergedReason(ksp_, &why), "KSPGetConvergedReason");
			report.iterations = int(its);
			report.converged  = why > 0;
			if (gamg_) {
				PetscReal rn = 0, bn = 0;
				check(KSPGetResidualNorm(ksp_, &rn), "KSPGetResidualNorm");
				check(VecNorm(b_, NORM_2, &bn), "VecNorm");
				report.residual = bn > 0 ? rn / bn : 0;
			}
			if (!report.converged) report.reason = KSPConvergedReasons[why];
			return report;
		}

	private:
		void makePattern(int n, const int* colStart, const int* row)
		{
			// the full symmetric matrix in compressed rows, each entry's source in the lower triangle
			n_ = n;
			lowerStart_.assign(colStart, colStart + n + 1);
			lowerRow_.assign(row, row + colStart[n]);
			if (nFullAsked_ > 0 && int(mapAsked_.size()) == n) map_ = mapAsked_, nFull_ = nFullAsked_, blockSize_ = blockAsked_;
			else {
				map_.resize(size_t(n));
				std::iota(map_.begin(), map_.end(), 0);
				nFull_ = n, blockSize_ = 1, nFullAsked_ = n, blockAsked_ = 1, mapAsked_ = map_;
			}
			const int        N = nFull_;
			std::vector<char> used(size_t(N), 0);
			for (int e = 0; e < n; ++e)
				used[size_t(map_[e])] = 1;
			std::vector<int> count(N + 1, 0);
			for (int j = 0; j < n; ++j)
				for (int k = colStart[j]; k < colStart[j + 1]; ++k) {
					++count[map_[row[k]] + 1];
					if (row[k] != j) ++count[map_[j] + 1];
				}
			for (int i = 0; i < N; ++i)
				if (!used[size_t(i)]) ++count[i + 1];
			std::partial_sum(count.begin(), count.end(), count.begin());
			rowStart_ = count;
			col_.assign(count[N], 0);
			source_.assign(count[N], 0);
			std::vector<int> next(count.begin(), count.end() - 1);
			for (int j = 0; j < n; ++j)
				for (int k = colStart[j]; k < colStart[j + 1]; ++k) {
					const int i = map_[row[k]], J = map_[j];
					col_[next[i]] = J, source_[next[i]++] = k;
					if (row[k] != j) col_[next[J]] = i, source_[next[J]++] = k;
				}
			for (int i = 0; i < N; ++i)
				if (!used[size_t(i)]) col_[next[i]] = i, source_[next[i]++] = -1 - (i % blockSize_);
			for (int i = 0; i < N; ++i) { // columns in order within each row
				std::vector<int> order(rowStart_[i + 1] - rowStart_[i]);
				std::iota(order.begin(), order.end(), rowStart_[i]);
				std::sort(order.begin(), order.end(), [&](int a, int b) { return col_[a] < col_[b]; });
				std::vector<int> c(order.size()), s(order.size());
				for (size_t t = 0; t < order.size(); ++t)
					c[t] = col_[order[t]], s[t] = source_[order[t]];
				std::copy(c.begin(), c.end(), col_.begin() + rowStart_[i]);
				std::copy(s.begin(), s.end(), source_.begin() + rowStart_[i]);
			}
			if (ksp_) KSPDestroy(&ksp_), ksp_ = nullptr, chosenType_ = nullptr;
			for (Mat* m : { &shell_, &op_, &pre_ })
				if (*m) MatDestroy(m);
			for (Vec* v : { &b_, &x_ })
				if (*v) VecDestroy(v);
			std::vector<double> zeros(col_.size(), 0.0);
			for (Mat* m : { &op_, &pre_ }) {
				check(MatCreate(PETSC_COMM_SELF, m), "MatCreate");
				check(MatSetSizes(*m, N, N, N, N), "MatSetSizes");
				check(MatSetType(*m, MATSEQAIJ), "MatSetType");
				check(MatSetBlockSize(*m, blockSize_), "MatSetBlockSize");
				check(MatSeqAIJSetPreallocationCSR(*m, rowStart_.data(), col_.data(), zeros.data()), "MatSeqAIJSetPreallocationCSR");
				check(MatSetOption(*m, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
				check(MatSetOption(*m, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
				check(MatSetOption(*m, MAT_SPD, PETSC_TRUE), "MatSetOption");
			}
			context_.K = op_;
			check(MatCreateShell(PETSC_COMM_SELF, N, N, N, N, &context_, &shell_), "MatCreateShell");
			check(MatShellSetOperation(shell_, MATOP_MULT, reinterpret_cast<void (*)(void)>(shellMult)), "MatShellSetOperation");
			check(VecCreateSeq(PETSC_COMM_SELF, N, &b_), "VecCreateSeq");
			check(VecDuplicate(b_, &x_), "VecDuplicate");
		}

		void copyValues(Mat m)
		{
			PetscScalar* a;
			check(MatSeqAIJGetArray(m, &a), "MatSeqAIJGetArray");
			std::copy(full_.begin(), full_.end(), a);
			check(MatSeqAIJRestoreArray(m, &a), "MatSeqAIJRestoreArray");
		}

		int fullRow(int e) const { return map_[size_t(e)]; }

		bool                             gamg_;
		int                              n_ = -1, nFull_ = 0, blockSize_ = 1, nFullAsked_ = 0, blockAsked_ = 1;
		std::vector<int>                 map_, mapAsked_;
		std::vector<int>                 lowerStart_, lowerRow_, rowStart_, col_, source_;
		std::vector<double>              full_;
		std::vector<std::vector<double>> nullModes_;
		bool                             haveNull_ = false;
		Mat                              op_ = nullptr, pre_ = nullptr, shell_ = nullptr;
		Vec                              b_ = nullptr, x_ = nullptr;
		KSP                              ksp_ = nullptr;
		KSPType                          chosenType_ = nullptr;
		ShellContext                     context_;
	};
} // namespace
} // namespace swelldem::linalg

extern "C" __attribute__((visibility("default"))) swelldem::linalg::SparseSolver* swelldem_petsc_open(const char* name, char* error, int errorSize)
{
	try {
		const std::string k(name ? name : "");
		if (k != "petsc-gamg" && k != "petsc-mumps") throw std::runtime_error("unknown PETSc solver '" + k + "' (petsc-gamg or petsc-mumps)");
		return new swelldem::linalg::PetscSolver(k == "petsc-gamg");
	} catch (const std::exception& e) {
		std::snprintf(error, size_t(errorSize), "%s", e.what());
		return nullptr;
	}
}
