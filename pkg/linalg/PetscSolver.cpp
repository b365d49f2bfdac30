// SPDX-License-Identifier: GPL-2.0-or-later
// libswelldem_petsc.so: SparseSolver over PETSc's C API (Debian's petsc-dev, real double, 32-bit
// indices) on PETSC_COMM_WORLD. In one process that is the process alone. Under mpirun -n P, rank 0
// is YADE with the scene and the ranks above run swelldem_petsc_worker: every operation of the
// solver on rank 0 first tells them which (a broadcast command), then all ranks carry it out
// together, rank 0 handing each rank its rows of the matrix and of every vector.
#include "SparseSolver.hpp"
#include <algorithm>
#include <chrono>
#include <thread>
#include <cmath>
#include <cstring>
#include <numeric>
#include <cstdio>
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
	bool finalized = false; // PetscFinalize done (at exit): nothing of PETSc's or MPI's may be called

	void initialise()
	{
		if (finalized) throw std::runtime_error("PETSc was already finalized");
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

	// -swelldem_<name> value, unless PETSC_OPTIONS already give it
	void defaultOption(const std::string& name, const char* value)
	{
		PetscBool set = PETSC_FALSE;
		check(PetscOptionsHasName(nullptr, "swelldem_", ("-" + name).c_str(), &set), "PetscOptionsHasName");
		if (!set) check(PetscOptionsSetValue(nullptr, ("-swelldem_" + name).c_str(), value), "PetscOptionsSetValue");
	}

	// PETSC_OPTIONS give every GAMG level's ICC fill (-swelldem_mg_levels_sub_pc_factor_levels),
	// read before defaultOption sets it: then no level's fill is chosen here
	bool allLevelsGiven()
	{
		static const bool given = [] {
			PetscBool set = PETSC_FALSE;
			check(PetscOptionsHasName(nullptr, "swelldem_", "-mg_levels_sub_pc_factor_levels", &set), "PetscOptionsHasName");
			return bool(set);
		}();
		return given;
	}

	MPI_Comm world() { return PETSC_COMM_WORLD; }
	int      rankOf()
	{
		int r = 0;
		MPI_Comm_rank(world(), &r);
		return r;
	}
	int sizeOf()
	{
		int p = 1;
		MPI_Comm_size(world(), &p);
		return p;
	}

	// The commands rank 0 broadcasts to the other ranks, one before each collective operation.
	enum Command : int { Open = 1, Close, Pattern, Values, Setup, Solve, Quit };

	void announce(Command c)
	{
		if (sizeOf() == 1) return;
		int code = c;
		MPI_Bcast(&code, 1, MPI_INT, 0, world());
	}

	template <class T> void broadcast(T* data, size_t count)
	{
		if (sizeOf() > 1 && count > 0) MPI_Bcast(data, int(count * sizeof(T)), MPI_BYTE, 0, world());
	}
	template <class T> void broadcast(std::vector<T>& v)
	{
		size_t n = v.size();
		broadcast(&n, 1);
		v.resize(n);
		broadcast(v.data(), n);
	}

	struct ShellContext {
		Mat                       K = nullptr;
		std::vector<RankOneTerm>  terms; // equations as global rows
		int                       lo = 0, hi = 0; // this rank's rows
	};

	// y = K x + sum u (v . x); each rank adds its rows' part of every v . x (one sum over the ranks)
	PetscErrorCode shellMult(Mat A, Vec x, Vec y)
	{
		ShellContext* ctx = nullptr;
		PetscCall(MatShellGetContext(A, &ctx));
		PetscCall(MatMult(ctx->K, x, y));
		if (ctx->terms.empty()) return 0;
		const PetscScalar* xv;
		PetscScalar*       yv;
		PetscCall(VecGetArrayRead(x, &xv));
		PetscCall(VecGetArray(y, &yv));
		const int           lo = ctx->lo, hi = ctx->hi;
		std::vector<double> s(ctx->terms.size(), 0.0);
		for (size_t t = 0; t < s.size(); ++t)
			for (int k = 0; k < 12; ++k) {
				const int r = ctx->terms[t].eq[k];
				if (r >= lo && r < hi) s[t] += ctx->terms[t].v[k] * xv[r - lo];
			}
		if (sizeOf() > 1) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s.data(), int(s.size()), MPI_DOUBLE, MPI_SUM, world()));
		for (size_t t = 0; t < s.size(); ++t)
			for (int k = 0; k < 12; ++k) {
				const int r = ctx->terms[t].eq[k];
				if (r >= lo && r < hi) yv[r - lo] += ctx->terms[t].u[k] * s[t];
			}
		PetscCall(VecRestoreArray(y, &yv));
		PetscCall(VecRestoreArrayRead(x, &xv));
		return 0;
	}

	// Rank 0 calls the SparseSolver interface; the ranks above call the collective parts (Pattern,
	// Values, Setup, Solve) from swelldem_petsc_worker with the command rank 0 announced. The global
	// matrix (the pattern, its values, the map of equations to rows) lives on rank 0 only; every rank
	// holds its own rows, blocks of whole bodies, as PETSc's AIJ matrices do.
	class PetscSolver : public SparseSolver {
	public:
		explicit PetscSolver(bool gamg)
		    : gamg_(gamg)
		{
			initialise();
			if (rankOf() == 0 && sizeOf() > 1) {
				// the ranks above hold one solver, the one rank 0 announced last
				if (live) throw std::runtime_error("under mpirun the ranks share one PETSc linear solver at a time, and another one is open");
				announce(Open);
				int g = gamg;
				broadcast(&g, 1);
				live = this;
			}
		}
		~PetscSolver() override { close(); }

		// Destroys the PETSc objects, on every rank together (MUMPS's factor is freed collectively);
		// a second call, or one after PetscFinalize (the objects went with it), does nothing.
		void close()
		{
			if (finalized || closed_) return;
			closed_ = true;
			if (live == this) {
				announce(Close);
				live = nullptr;
			}
			destroyObjects();
		}
		static inline PetscSolver* live = nullptr; // rank 0 under mpirun: the solver the ranks above hold

		const char* name() const override { return gamg_ ? "petsc-gamg" : "petsc-mumps"; }
		bool        iterative() const override { return gamg_; }

		void setBlocks(int n, int blockSize, int nFull, const int* fullOf) override
		{
			blockAsked_ = blockSize, nFullAsked_ = nFull, mapAsked_.assign(fullOf, fullOf + n);
		}

		void setMatrix(int n, const int* colStart, const int* row, const double* value) override
		{
			const int  nnz  = colStart[n];
			const bool same = n == n_ && size_t(nnz) == lowerRow_.size() && std::equal(colStart, colStart + n + 1, lowerStart_.begin())
			                  && std::equal(row, row + nnz, lowerRow_.begin()) && mapAsked_ == map_ && nFullAsked_ == nFull_;
			if (!same) {
				makePattern(n, colStart, row);
				announce(Pattern);
				distributePattern();
			}
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
			announce(Values);
			distributeValues();
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
			announce(Setup);
			setupAll();
		}

		SolveReport solve(const double* b, double* x, double rtol, const std::vector<RankOneTerm>& terms, bool symmetric, int gmresLimit) override
		{
			if (!ksp_) throw std::runtime_error("PETSc solve before its setup");
			// the terms' equations as global rows, the right-hand side on rank 0's copy of the vector
			context_.terms = terms;
			for (RankOneTerm& t : context_.terms)
				for (int k = 0; k < 12; ++k)
					if (t.eq[k] >= 0) t.eq[k] = fullRow(t.eq[k]);
			PetscScalar* a;
			check(VecGetArray(onZero_, &a), "VecGetArray");
			std::fill(a, a + nFull_, 0.0);
			for (int e = 0; e < n_; ++e)
				a[fullRow(e)] = b[e];
			check(VecRestoreArray(onZero_, &a), "VecRestoreArray");
			announce(Solve);
			const SolveReport report = solveAll(rtol, symmetric, gmresLimit);
			const PetscScalar* xv;
			check(VecGetArrayRead(onZero_, &xv), "VecGetArrayRead");
			for (int e = 0; e < n_; ++e)
				x[e] = xv[fullRow(e)];
			check(VecRestoreArrayRead(onZero_, &xv), "VecRestoreArrayRead");
			return report;
		}

		// The collective parts, on every rank (rank 0's arguments are broadcast inside).

		void distributePattern()
		{
			int sizes[2] = { nFull_, blockSize_ };
			broadcast(sizes, 2);
			nFull_ = sizes[0], blockSize_ = sizes[1];
			const int P = sizeOf(), me = rankOf(), blocks = nFull_ / blockSize_;
			// whole bodies a rank, as even as the blocks allow
			std::vector<int> first(static_cast<size_t>(P) + 1);
			for (int r = 0; r <= P; ++r)
				first[size_t(r)] = r == P ? nFull_ : int(long(blocks) * r / P) * blockSize_;
			context_.lo = first[size_t(me)], context_.hi = first[size_t(me) + 1];
			const int m = context_.hi - context_.lo;
			// each rank's rows of the compressed-row pattern: row lengths, then columns
			std::vector<int> lengths(static_cast<size_t>(m));
			std::vector<int> counts(static_cast<size_t>(P)), starts(static_cast<size_t>(P));
			std::vector<int> allLengths;
			if (me == 0) {
				allLengths.resize(size_t(nFull_));
				for (int i = 0; i < nFull_; ++i)
					allLengths[size_t(i)] = rowStart_[size_t(i) + 1] - rowStart_[size_t(i)];
			}
			for (int r = 0; r < P; ++r)
				counts[size_t(r)] = first[size_t(r) + 1] - first[size_t(r)], starts[size_t(r)] = first[size_t(r)];
			MPI_Scatterv(allLengths.data(), counts.data(), starts.data(), MPI_INT, lengths.data(), m, MPI_INT, 0, world());
			localStart_.assign(size_t(m) + 1, 0);
			std::partial_sum(lengths.begin(), lengths.end(), localStart_.begin() + 1);
			if (me == 0)
				for (int r = 0; r < P; ++r)
					starts[size_t(r)] = rowStart_[size_t(first[size_t(r)])], counts[size_t(r)] = rowStart_[size_t(first[size_t(r) + 1])] - starts[size_t(r)];
			valueCounts_ = counts, valueStarts_ = starts;
			localCol_.resize(size_t(localStart_.back()));
			MPI_Scatterv(col_.data(), counts.data(), starts.data(), MPI_INT, localCol_.data(), int(localCol_.size()), MPI_INT, 0, world());

			destroyObjects();
			const int           N = nFull_;
			std::vector<double> zeros(localCol_.size(), 0.0);
			for (Mat* a : { &op_, &pre_ }) {
				check(MatCreate(world(), a), "MatCreate");
				check(MatSetSizes(*a, m, m, N, N), "MatSetSizes");
				check(MatSetType(*a, MATAIJ), "MatSetType");
				check(MatSetBlockSize(*a, blockSize_), "MatSetBlockSize");
				check(MatSeqAIJSetPreallocationCSR(*a, localStart_.data(), localCol_.data(), zeros.data()), "MatSeqAIJSetPreallocationCSR");
				check(MatMPIAIJSetPreallocationCSR(*a, localStart_.data(), localCol_.data(), zeros.data()), "MatMPIAIJSetPreallocationCSR");
				check(MatSetOption(*a, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
				check(MatSetOption(*a, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "MatSetOption");
				check(MatSetOption(*a, MAT_SPD, PETSC_TRUE), "MatSetOption");
				check(MatSetOption(*a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
			}
			context_.K = op_;
			check(MatCreateShell(world(), m, m, N, N, &context_, &shell_), "MatCreateShell");
			check(MatShellSetOperation(shell_, MATOP_MULT, reinterpret_cast<void (*)(void)>(shellMult)), "MatShellSetOperation");
			check(MatCreateVecs(op_, &x_, &b_), "MatCreateVecs");
			// the whole vector on rank 0 (empty elsewhere): b goes out from it, x comes back to it
			check(VecScatterCreateToZero(x_, &toZero_, &onZero_), "VecScatterCreateToZero");
		}

		// this rank's values of the current matrix (rank 0's full_) into op_
		void distributeValues()
		{
			localValues_.resize(localCol_.size());
			MPI_Scatterv(full_.data(), valueCounts_.data(), valueStarts_.data(), MPI_DOUBLE, localValues_.data(), int(localValues_.size()),
			             MPI_DOUBLE, 0, world());
			setLocalValues(op_);
		}

		// the KSP and its preconditioner, with the options of the moment (PETSC_OPTIONS first)
		void createKsp()
		{
			check(KSPCreate(world(), &ksp_), "KSPCreate");
			check(KSPSetOptionsPrefix(ksp_, "swelldem_"), "KSPSetOptionsPrefix");
			PC pc;
			check(KSPGetPC(ksp_, &pc), "KSPGetPC");
			if (gamg_) {
				check(KSPSetType(ksp_, KSPCG), "KSPSetType");
				check(PCSetType(pc, PCGAMG), "PCSetType");
				// The levels smooth with an incomplete Cholesky factor of the assembled matrix, one
				// block a rank, not the operator with its rank-one terms. A packing's spheres have
				// few contacts (6.5 a sphere), so neighbours turn against each other at little cost;
				// such local rolling modes are neither in the rigid-body coarse space nor damped by
				// a sphere's own 6 x 6 block. On the finest level ICC(1) couples each sphere to its
				// neighbours' rotations, and the CG iterations stop growing with the size (ISR cube,
				// first step, a solve: 12 mm 11, 20 mm 16, 30 mm 23 against 40, 67, 362 with
				// point-block Jacobi). The coarser levels take ICC(0): aggregates of aggregates are
				// dense (40 mm: 7,512 rows of 1,177 entries), where one fill level makes a nearly
				// full factor (40 mm first step: set-up 28 s against 89 s, 106 CG iterations
				// against 103). PETSC_OPTIONS given with the prefix swelldem_ take precedence.
				allLevelsGiven(); // read now, before defaultOption gives every level its fill
				defaultOption("mg_levels_pc_type", "bjacobi");
				defaultOption("mg_levels_sub_pc_type", "icc");
				defaultOption("mg_levels_sub_pc_factor_levels", "0");
				// two Chebyshev sweeps: 25 mm, 18 CG iterations a solve against 14 with four, but
				// a shorter step (24.2 against 26.8 s)
				defaultOption("mg_levels_ksp_max_it", "2");
			} else {
				check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
				check(PCSetType(pc, PCCHOLESKY), "PCSetType");
				check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
				// MUMPS sizes the factor's workspace from its analysis's estimate plus ICNTL(14) per
				// cent; across ranks the estimate falls short (12 mm ISR cube on 2 ranks: INFOG(1) =
				// -9 at PETSc's default), with a 100 % margin it holds
				if (sizeOf() > 1) defaultOption("mat_mumps_icntl_14", "100");
			}
			check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
			// after the user's options: the shell operator (its rank-one terms) has no entries a
			// smoother could read, so the preconditioner works on the assembled matrix whatever
			// PETSC_OPTIONS say (PETSc's own SOR on the shell ends the process)
			if (gamg_) check(PCSetUseAmat(pc, PETSC_FALSE), "PCSetUseAmat");
			check(KSPGetType(ksp_, &chosenType_), "KSPGetType");
		}

		void setupAll()
		{
			setLocalValues(pre_);
			if (!ksp_) createKsp();
			int modes = gamg_ && haveNull_ ? int(nullModes_.size()) : 0;
			broadcast(&modes, 1);
			if (modes > 0) {
				std::vector<Vec> vecs(static_cast<size_t>(modes));
				for (int k = 0; k < modes; ++k) {
					if (rankOf() == 0) {
						PetscScalar* a;
						check(VecGetArray(onZero_, &a), "VecGetArray");
						std::copy(nullModes_[size_t(k)].begin(), nullModes_[size_t(k)].end(), a);
						check(VecRestoreArray(onZero_, &a), "VecRestoreArray");
					}
					check(VecDuplicate(x_, &vecs[size_t(k)]), "VecDuplicate");
					fromZero(vecs[size_t(k)]);
				}
				MatNullSpace nsp;
				check(MatNullSpaceCreate(world(), PETSC_FALSE, PetscInt(vecs.size()), vecs.data(), &nsp), "MatNullSpaceCreate");
				check(MatSetNearNullSpace(pre_, nsp), "MatSetNearNullSpace");
				check(MatNullSpaceDestroy(&nsp), "MatNullSpaceDestroy");
				for (Vec& v : vecs)
					VecDestroy(&v);
				haveNull_ = false;
			}
			for (;;) {
				check(KSPSetReusePreconditioner(ksp_, PETSC_FALSE), "KSPSetReusePreconditioner");
				check(KSPSetOperators(ksp_, gamg_ ? shell_ : pre_, pre_), "KSPSetOperators");
				check(KSPSetUp(ksp_), "KSPSetUp");
				if (!gamg_ || !finestNeedsFill()) break;
				// a new KSP reads the finest level's option; pre_ keeps its values and near-null space
				KSPDestroy(&ksp_), chosenType_ = nullptr;
				createKsp();
			}
			if (!gamg_) checkFactor();
			check(KSPSetReusePreconditioner(ksp_, PETSC_TRUE), "KSPSetReusePreconditioner");
		}

		// PCMG numbers its levels from the coarsest, so the finest level's options are known by number
		// only once GAMG has coarsened. When the hierarchy just made smoothed its finest level without
		// the fill (the first set-up in a process, or a pattern that coarsens to another number of
		// levels), the option is set and a new KSP built with it (a PC reset and set up again in place
		// gave an indefinite preconditioner at 40 mm): a set-up more, once. Later set-ups keep the levels.
		bool finestNeedsFill()
		{
			PC       pc;
			PetscInt levels = 0;
			check(KSPGetPC(ksp_, &pc), "KSPGetPC");
			check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
			if (levels < 2 || allLevelsGiven()) return false;
			const std::string name = "-swelldem_mg_levels_" + std::to_string(levels - 1) + "_sub_pc_factor_levels";
			if (name == finestOption_) return false;
			// PETSc's look-up of a numbered level falls back to every level's option: the user's own
			// option for this level is found in the list itself
			char* all = nullptr;
			check(PetscOptionsGetAll(nullptr, &all), "PetscOptionsGetAll");
			const bool given = (" " + std::string(all ? all : "") + " ").find(" " + name + " ") != std::string::npos;
			PetscFree(all);
			if (given) return false;
			if (!finestOption_.empty()) check(PetscOptionsClearValue(nullptr, finestOption_.c_str()), "PetscOptionsClearValue");
			check(PetscOptionsSetValue(nullptr, name.c_str(), "1"), "PetscOptionsSetValue");
			finestOption_ = name;
			return true;
		}

		// MUMPS sizes the factor's workspace from its analysis's estimate plus ICNTL(14) per cent, and
		// the estimate can fall short as contacts break (12 mm ISR cube on 2 ranks at a 0 % margin:
		// INFOG(1) = -9 at step 34). Such a factorization is made again, from its analysis, with
		// twice the margin, up to 4 times; any other failure stops the run with MUMPS's own code
		// rather than giving a NaN move. INFOG is global, so every rank decides alike.
		void checkFactor()
		{
			for (int attempt = 0;; ++attempt) {
				PC       pc;
				Mat      F;
				PetscInt info1 = 0, info2 = 0, margin = 0;
				check(KSPGetPC(ksp_, &pc), "KSPGetPC");
				check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
				check(MatMumpsGetInfog(F, 1, &info1), "MatMumpsGetInfog");
				check(MatMumpsGetInfog(F, 2, &info2), "MatMumpsGetInfog");
				if (info1 >= 0) return;
				const bool room = info1 == -8 || info1 == -9;
				if (!room || attempt == 4)
					throw std::runtime_error("MUMPS's factorization failed: INFOG(1) = " + std::to_string(info1) + ", INFOG(2) = " + std::to_string(info2)
					                         + (room ? " (workspace too small after 4 larger margins: raise -swelldem_mat_mumps_icntl_14 in PETSC_OPTIONS)" : ""));
				check(MatMumpsGetIcntl(F, 14, &margin), "MatMumpsGetIcntl");
				// a failed factor is not factored again: the PC starts anew, reading the wider margin
				check(PetscOptionsSetValue(nullptr, "-swelldem_mat_mumps_icntl_14", std::to_string(2 * margin + 20).c_str()), "PetscOptionsSetValue");
				check(PCReset(pc), "PCReset");
				check(KSPSetOperators(ksp_, pre_, pre_), "KSPSetOperators");
				check(KSPSetUp(ksp_), "KSPSetUp");
			}
		}

		// the right-hand side is on rank 0's copy (onZero_); the solution comes back there
		SolveReport solveAll(double rtol, bool symmetric, int gmresLimit)
		{
			int sym = symmetric;
			broadcast(&sym, 1);
			broadcast(&rtol, 1);
			broadcast(&gmresLimit, 1);
			broadcast(context_.terms);
			SolveReport report;
			// The terms' sliding contacts make A unsymmetric: GMRES, with the preconditioner on the
			// right so that the residual it measures is A's own; CG (the unpreconditioned residual) otherwise.
			const bool cg = sym || context_.terms.empty();
			if (gamg_) {
				if (chosenType_ && (std::strcmp(chosenType_, KSPCG) == 0 || std::strcmp(chosenType_, KSPGMRES) == 0)) {
					check(KSPSetType(ksp_, cg ? KSPCG : KSPGMRES), "KSPSetType");
					// Each rank-one term can put one eigenvalue of the preconditioned operator outside
					// the cluster GAMG gives K; a restart shorter than the terms loses them at every
					// cycle and stagnates (20 mm ISR cube, step 5, 106 terms: no convergence at 5000
					// iterations with 100). So a cycle holds twice the terms and the cluster's own
					// iterations.
					if (!cg) check(KSPGMRESSetRestart(ksp_, PetscInt(std::clamp<size_t>(2 * context_.terms.size() + 60, 100, 600))), "KSPGMRESSetRestart");
					check(KSPSetPCSide(ksp_, cg ? PC_LEFT : PC_RIGHT), "KSPSetPCSide");
					check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
				}
				// CG's cap is a safeguard. GMRES's is the rule: a cracking round's tangent has hundreds of
				// sliding contacts' columns, each an eigenvalue off GAMG's cluster, and is close to
				// singular; GMRES then takes hundreds of iterations a solve (20 mm ISR cube, day 100 to 316:
				// 195 on average, up to 936, some ended by a breakdown) for a move that the round's next
				// iterations, by Newton with the active set changing or by relaxation after changingLimit,
				// revise anyway. At 100 the step took 282 s against more than 1,816 s uncapped.
				check(KSPSetTolerances(ksp_, rtol, 0.0, PETSC_DEFAULT, cg ? 5000 : gmresLimit), "KSPSetTolerances");
			}
			fromZero(b_);
			check(KSPSolve(ksp_, b_, x_), "KSPSolve");
			check(VecScatterBegin(toZero_, x_, onZero_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
			check(VecScatterEnd(toZero_, x_, onZero_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
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
			report.atLimit = gamg_ && !cg && why == KSP_DIVERGED_ITS;
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
		}

		// the PETSc objects of the current pattern (PETSc's Destroy calls null the handles)
		void destroyObjects()
		{
			if (ksp_) KSPDestroy(&ksp_), chosenType_ = nullptr;
			for (Mat* a : { &shell_, &op_, &pre_ })
				if (*a) MatDestroy(a);
			if (toZero_) VecScatterDestroy(&toZero_);
			for (Vec* v : { &b_, &x_, &onZero_ })
				if (*v) VecDestroy(v);
		}

		void setLocalValues(Mat a)
		{
			for (int i = 0; i + context_.lo < context_.hi; ++i) {
				const PetscInt r = context_.lo + i, k = localStart_[size_t(i)];
				check(MatSetValues(a, 1, &r, localStart_[size_t(i) + 1] - k, localCol_.data() + k, localValues_.data() + k, INSERT_VALUES),
				      "MatSetValues");
			}
			check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
			check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
		}

		// v (distributed) = rank 0's onZero_
		void fromZero(Vec v)
		{
			check(VecScatterBegin(toZero_, onZero_, v, INSERT_VALUES, SCATTER_REVERSE), "VecScatterBegin");
			check(VecScatterEnd(toZero_, onZero_, v, INSERT_VALUES, SCATTER_REVERSE), "VecScatterEnd");
		}

		int fullRow(int e) const { return map_[size_t(e)]; }

		bool gamg_;
		bool closed_ = false;
		// rank 0: the global system and the map of the caller's equations to its rows
		int                              n_ = -1, nFull_ = 0, blockSize_ = 1, nFullAsked_ = 0, blockAsked_ = 1;
		std::vector<int>                 map_, mapAsked_;
		std::vector<int>                 lowerStart_, lowerRow_, rowStart_, col_, source_;
		std::vector<double>              full_;
		std::vector<std::vector<double>> nullModes_;
		bool                             haveNull_ = false;
		std::vector<int>                 valueCounts_, valueStarts_; // each rank's share of col_ and full_
		// every rank: its rows (context_.lo to hi) in compressed rows with global columns
		std::vector<int>                 localStart_, localCol_;
		std::vector<double>              localValues_;
		Mat                              op_ = nullptr, pre_ = nullptr, shell_ = nullptr;
		Vec                              b_ = nullptr, x_ = nullptr, onZero_ = nullptr;
		VecScatter                       toZero_ = nullptr;
		KSP                              ksp_ = nullptr;
		KSPType                          chosenType_ = nullptr;
		// the finest level's fill, set here; PETSc's options are the process's, as this is
		static inline std::string finestOption_;
		ShellContext                     context_;
	};
} // namespace
} // namespace swelldem::linalg

using swelldem::linalg::PetscSolver;

extern "C" __attribute__((visibility("default"))) swelldem::linalg::SparseSolver* swelldem_petsc_open(const char* name, char* error, int errorSize)
{
	try {
		const std::string k(name ? name : "");
		if (k != "petsc-gamg" && k != "petsc-mumps") throw std::runtime_error("unknown PETSc solver '" + k + "' (petsc-gamg or petsc-mumps)");
		return new PetscSolver(k == "petsc-gamg");
	} catch (const std::exception& e) {
		std::snprintf(error, size_t(errorSize), "%s", e.what());
		return nullptr;
	}
}

// Rank 0 at exit under mpirun: releases the ranks above (which wait for a command, whether or not
// the run used them) and finalizes PETSc and MPI, so that mpirun ends with rank 0's exit status.
extern "C" __attribute__((visibility("default"))) void swelldem_petsc_release()
{
	using namespace swelldem::linalg;
	if (finalized) return;
	try {
		initialise();
		if (PetscSolver::live) PetscSolver::live->close(); // the scene, and its solver, outlive this call
		announce(Quit);
		PetscFinalize();
	} catch (const std::exception& e) {
		std::fprintf(stderr, "swelldem: releasing the MPI ranks failed: %s\n", e.what());
	}
	finalized = true;
}

// The ranks above 0 (scripts/yade-swelldem runs swelldem-solve-worker there): carry out rank 0's
// commands until it quits. Returns the process's exit status; a failure aborts the whole job, since
// rank 0 would otherwise wait for this rank in its next collective call.
extern "C" __attribute__((visibility("default"))) int swelldem_petsc_worker()
{
	using namespace swelldem::linalg;
	int rank = -1;
	try {
		initialise();
		rank = rankOf();
		if (rank == 0) throw std::runtime_error("rank 0 is YADE's (scripts/yade-swelldem); the worker runs on the ranks above it");
		std::unique_ptr<PetscSolver> s;
		for (;;) {
			int c = 0;
			MPI_Bcast(&c, 1, MPI_INT, 0, world());
			if (c == Quit) break;
			if (c == Open) {
				int gamg = 0;
				broadcast(&gamg, 1);
				s.reset(new PetscSolver(gamg != 0));
				continue;
			}
			if (c == Close) {
				s.reset();
				continue;
			}
			if (!s) throw std::runtime_error("command " + std::to_string(c) + " before a solver was opened");
			switch (c) {
			case Pattern: s->distributePattern(); break;
			case Values: s->distributeValues(); break;
			case Setup: s->setupAll(); break;
			case Solve: s->solveAll(0.0, false, 0); break;
			default: throw std::runtime_error("unknown command " + std::to_string(c));
			}
		}
		s.reset();
		PetscFinalize();
		finalized = true;
		return 0;
	} catch (const std::exception& e) {
		std::fprintf(stderr, "swelldem solve worker (MPI rank %d): %s\n", rank, e.what());
		// A collective failure (MUMPS's factor, a PETSc error) stops rank 0's run too: it records
		// where and why and writes its results before this rank ends the job
		std::this_thread::sleep_for(std::chrono::seconds(10));
		MPI_Abort(MPI_COMM_WORLD, 1);
		return 1;
	}
}
