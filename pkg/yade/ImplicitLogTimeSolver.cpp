// SPDX-License-Identifier: GPL-2.0-or-later
#include "ImplicitLogTimeSolver.hpp"
#include "core/Validate.hpp"
#include "SparseSolver.hpp"
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <tuple>
#include <cmath>
#include <omp.h>
#include <unistd.h>

namespace yade {
namespace core = swelldem::core;
using Vector2r = Eigen::Matrix<Real, 2, 1>;

namespace {
	// Lower-triangle index pairs (row a >= column b) of a contact's n x n block over its DOFs (body
	// 1's, then body 2's): n = 6 in 2D (x, y, rz each), 12 in 3D (x, y, z, rx, ry, rz each).
	struct PairTable {
		int n, size, a[78], b[78];
		explicit PairTable(int blockSize)
		    : n(blockSize)
		    , size(0)
		{
			for (int j = 0; j < n; ++j)
				for (int i = j; i < n; ++i)
					a[size] = i, b[size] = j, ++size;
		}
	};
	const PairTable kPairs2D(6), kPairs3D(12);
}

struct ImplicitLinearSystem {
	using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
	int                                                nb = 3;     // DOFs a body: 2D x, y, rz; 3D x, y, z, rx, ry, rz
	const PairTable*                                   pairs = &kPairs2D; // of a contact's 2 nb x 2 nb block
	std::vector<int>                                   dofOf;      // nb x body id + axis -> equation, -1 if held
	std::vector<unsigned>                              dofMasks;   // blocked DOFs of each body when dofOf was made
	std::vector<std::pair<int, int>>                   graph;      // the real contacts the pattern was made for
	std::vector<int>                                   slots;      // per contact, the entries of its block's lower triangle (-1: held)
	std::vector<int>                                   diagSlot;   // per equation
	std::vector<char>                                  isRotation; // per equation: a rotation
	double                                             rotationScale = 0; // median diagonal of the rotations, this assembly's
	std::vector<char>                                  active;     // per contact: its core::ContactLaw::Mode
	SpMat                                              K;
	Eigen::CholmodDecomposition<SpMat, Eigen::Lower>   chol;
	std::unique_ptr<swelldem::linalg::SparseSolver>    petsc; // instead of chol: linearSolver petsc-gamg or petsc-mumps
	bool                                               acrossInK = false; // K's values hold the 3D sliding contacts' across stiffness (factor())
	std::vector<Eigen::VectorXd>                       z; // K^-1 u of each kept low-rank column (lowRankColumns), for the factor in hand
	int                                                nEq = 0;
	bool                                               haveFactor = false;
	// This iteration's: the real contacts, the discs in a mechanism, the columns, each contact's
	// (kn, ks) in its current state and the contacts whose (kn, ks) differ from the factored ones
	std::vector<const Interaction*> contacts;
	std::vector<char>               mech;
	std::vector<char>               kink; // per contact: closed in this solve whatever its state in YADE (settleKinks)
	std::vector<LowRankColumn>      columns;
	std::vector<Real>               stiffness;
	long                            changed = 0;
	std::vector<Real>               deltaDiag; // per equation, the diagonal change of the changed contacts
	// 3D sliding contacts' stiffness across their slip (contact, its components on the tangents,
	// ks |Fs| / |Fs trial|): it enters a factor when one is made, not K's values (factor())
	std::vector<std::array<Real, 4>> across;
	std::vector<int>                touched;   // the equations deltaDiag touches
	int nc() const { return 2 * nb; } // a contact's DOFs
	// a contact's equations over its DOFs (body 1's, then body 2's), -1 where held and past nc()
	void equationsOf(const Interaction* I, int eq[LowRankColumn::kSize]) const
	{
		for (int d = 0; d < nb; ++d)
			eq[d] = dofOf[nb * I->id1 + d], eq[nb + d] = dofOf[nb * I->id2 + d];
		std::fill(eq + nc(), eq + LowRankColumn::kSize, -1);
	}
	void addColumn(const Interaction* I, int type, Real value, const Real* a, const Real* b)
	{
		LowRankColumn col { I->id1, I->id2, type, value, {}, {}, {} };
		equationsOf(I, col.eq);
		for (int k = 0; k < nc(); ++k)
			col.u[k] = value * a[k], col.v[k] = b[k];
		columns.push_back(col);
	}
	// the index of entry (row, col) of the lower triangle in K's values
	int slotOf(int row, int col) const
	{
		const int* inner = K.innerIndexPtr();
		const int  lo = K.outerIndexPtr()[col], hi = K.outerIndexPtr()[col + 1];
		return int(std::lower_bound(inner + lo, inner + hi, row) - inner);
	}
};

namespace {
	// Debian's CHOLMOD opens OpenMP regions of a fixed 4 threads inside its supernodal factorization
	// (its compile-time CHOLMOD_OMP_NUM_THREADS), whatever YADE's -j says. On this 2-core machine
	// their barriers took a third of a 100 mm damage run (futex waits); serial, the factorizations
	// cost 25 % less (docs/performance.md, 1b). No active OpenMP level runs them on the calling thread.
	struct SerialOpenMP {
		const int levels = omp_get_max_active_levels();
		SerialOpenMP() { omp_set_max_active_levels(0); }
		~SerialOpenMP() { omp_set_max_active_levels(levels); }
	};

	// A real interaction's tangent and its state (core::ContactLaw::Mode; 0 for a stock contact):
	// kn, ks [N/m] of the state the contact is in, and for a sliding contact the slope of its shear
	// force along the Coulomb cone, slide = dFs/d(opening) = -sign(Fs) tan(phi_res) kn [N/m]; in 3D
	// slide = -tan(phi_res) kn along the shear force's direction (dir: its components on the two
	// tangents; 2D: 1, 0), and across it the radial return's stiffness dir[2] = ks |Fs| / |Fs trial|
	// (the trial shear turns the force without changing its size).
	// sticking: a sliding contact enters as sticking (the elastic predictor's tangent).
	// closed: a broken contact taken as closed, kn'' alone, whatever its state in YADE (settleKinks:
	// its shear is left to the next iteration, which has the state it lands in).
	char contactTangent(Law2_ScGeom_SwellPhys_AgingSwelling& law2, const Interaction* I, Real& kn, Real& ks, Real& slide, Real dir[3], bool sticking,
	                    bool closed)
	{
		slide = 0, dir[0] = 1, dir[1] = 0, dir[2] = 0;
		const auto* sp = dynamic_cast<const SwellPhys*>(I->phys.get());
		if (!sp) {
			const auto* p = static_cast<const NormShearPhys*>(I->phys.get());
			kn = p->kn, ks = p->ks;
			return 0;
		}
		using Mode   = core::ContactLaw::Mode;
		const Mode m0 = law2.lawFor(*sp->kind).mode(sp->state);
		if (closed) {
			kn = sp->state.kn, ks = 0;
			return char(m0);
		}
		const Mode m  = sticking && m0 == Mode::Sliding ? Mode::Sticking : m0;
		kn           = m == Mode::Open ? 0 : sp->state.kn;
		ks           = (m == Mode::Intact || m == Mode::Sticking) ? sp->state.ks : 0;
		if (m == Mode::Sliding) {
			const Real tanPhi = std::tan(law2.lawFor(*sp->kind).params().strength.residualFrictionAngle);
			if (sp->dim == 3) {
				const core::ContactState& st    = sp->state;
				const Real                size  = std::hypot(st.trial.Fs, st.trial.Fs2);
				const Real                trial = std::hypot(st.committed.Fs + st.ks * (st.shearStep - st.duOffsetS),
                                                             st.committed.Fs2 + st.ks * (st.shearStep2 - st.duOffsetS2));
				if (size > 0) slide = -tanPhi * st.kn, dir[0] = st.trial.Fs / size, dir[1] = st.trial.Fs2 / size;
				if (trial > 0 && law2.shearFromStepStart) dir[2] = st.ks * std::min(size / trial, Real(1));
			} else
				slide = -(sp->state.trial.Fs > 0 ? 1 : -1) * tanPhi * sp->state.kn;
		}
		return char(m0);
	}

	// A contact's rows over its DOFs (body 1's, then body 2's): its normal opening bn and its shear
	// slips bs (2D: along ez x n; 3D: along the law's first tangent, SwellPhys.frameAxis) and bs2 (3D:
	// the second tangent), as YADE's ScGeom measures them from the bodies' moves, a rotation turning
	// the contact point at lever arm r - penetration / 2. A stock contact's shear in 3D is isotropic:
	// any pair of tangents gives its stiffness. Returns the number of DOFs, 6 or 12.
	int contactRows(const Interaction* I, int nb, Real bn[12], Real bs[12], Real bs2[12])
	{
		const auto*     g  = static_cast<const ScGeom*>(I->geom.get());
		const Vector3r& n  = g->normal;
		const Real      r1 = g->radius1 - 0.5 * g->penetrationDepth, r2 = g->radius2 - 0.5 * g->penetrationDepth;
		if (nb == 3) {
			const Real n2[6] = { -n[0], -n[1], 0, n[0], n[1], 0 };
			const Real s2[6] = { n[1], -n[0], -r1, -n[1], n[0], -r2 };
			std::copy(n2, n2 + 6, bn), std::copy(s2, s2 + 6, bs);
			return 6;
		}
		const auto* sp   = dynamic_cast<const SwellPhys*>(I->phys.get());
		int         axis = 0;
		if (sp)
			axis = sp->frameAxis;
		else
			n.cwiseAbs().minCoeff(&axis);
		const auto [t1, t2] = Law2_ScGeom_SwellPhys_AgingSwelling::tangents(n, axis);
		// slip along t: t.(u2 - u1) - r1 theta1.(n x t) - r2 theta2.(n x t); n x t1 = t2, n x t2 = -t1
		for (int d = 0; d < 3; ++d) {
			bn[d] = -n[d], bn[3 + d] = 0, bn[6 + d] = n[d], bn[9 + d] = 0;
			bs[d] = -t1[d], bs[3 + d] = -r1 * t2[d], bs[6 + d] = t1[d], bs[9 + d] = -r2 * t2[d];
			bs2[d] = -t2[d], bs2[3 + d] = r1 * t1[d], bs2[6 + d] = t2[d], bs2[9 + d] = r2 * t1[d];
		}
		return 12;
	}

	// Adds the 3D sliding contacts' stiffness across their slip (S.across) to K's values v.
	void addAcross(const ImplicitLinearSystem& S, double* v)
	{
		const PairTable& P = *S.pairs;
		for (const auto& a : S.across) {
			const size_t c = size_t(a[0]);
			Real         bn[12], bs[12], bs2[12], row[12];
			contactRows(S.contacts[c], S.nb, bn, bs, bs2);
			for (int k = 0; k < 12; ++k)
				row[k] = -a[2] * bs[k] + a[1] * bs2[k];
			const int* slot = &S.slots[P.size * c];
			for (int k = 0; k < P.size; ++k)
				if (slot[k] >= 0) v[slot[k]] += a[3] * row[P.a[k]] * row[P.b[k]];
		}
	}
}

ImplicitLogTimeSolver::ImplicitLogTimeSolver()
{
	tolerance      = 1e-10;
	minIterations  = 1;
	colliderPeriod = 1;
	iterationName  = "Newton";
	// Newton needs a residual that depends on the state reached, not on the iterations' path
	shearFromStepStart = true;
	// under mpirun auto takes petsc-gamg, where PETSc can be loaded; a run keeps the solver its first
	// system took (auto on one process: often cholmod), also when it goes on after O.load under mpirun
	sharesRanks = [this] {
		if (!linearSolverUsed.empty()) return linearSolverUsed != "cholmod";
		return linearSolver == "auto" ? swelldem::linalg::petscUnavailable().empty() : linearSolver != "cholmod";
	};
	progressDetail     = [this] {
		return " (" + std::to_string(relaxationIterations - relaxationAtStepStart) + " relaxation, "
		       + std::to_string(factorizations - factorizationsAtStepStart) + (linearSolverUsed == "petsc-gamg" ? " preconditioner set-ups, " + std::to_string(krylovIterations - krylovAtStepStart) + " Krylov iterations" : " factorizations")
		       + (activeChanges > 0 ? ", " + std::to_string(activeChanges) + " contacts changing state in the last iteration" : std::string())
		       + (fallback ? ", finished by dynamic relaxation: fallback" : std::string()) + ")";
	};
	beforeCommit = [this] {
		if (!fallback) return;
		fallbackSteps.push_back(step);
		fallbackRelaxation.push_back(int(relaxationIterations - fallbackRelaxStart));
		fallbackWall.push_back(wallNow() - (stepWall.empty() ? 0.0 : stepWall.back()));
	};
}

ImplicitLogTimeSolver::~ImplicitLogTimeSolver() { }

void ImplicitLogTimeSolver::postLoad()
{
	LogTimeSolver::postLoad();
	core::require(regularization >= 0 && regularization < 1e-3, "ImplicitLogTimeSolver.regularization", regularization, "0 <= regularization < 1e-3");
	core::require(rotationRegularization < 1, "ImplicitLogTimeSolver.rotationRegularization", rotationRegularization,
	              "rotationRegularization < 1 (< 0: the dimension's default)");
	core::require(refactorTolerance >= 0 && refactorTolerance < 1, "ImplicitLogTimeSolver.refactorTolerance", refactorTolerance, "0 <= refactorTolerance < 1");
	core::require(maxMove > 0 && maxMove <= 1, "ImplicitLogTimeSolver.maxMove", maxMove, "0 < maxMove <= 1");
	core::require(mechanismMove >= 0 && mechanismMove < 1, "ImplicitLogTimeSolver.mechanismMove", mechanismMove, "0 <= mechanismMove < 1");
	core::require(newtonLimit >= 1, "ImplicitLogTimeSolver.newtonLimit", newtonLimit, ">= 1");
	core::require(changingLimit >= -1, "ImplicitLogTimeSolver.changingLimit", changingLimit, ">= 0 (0: none), or -1 for the dimension's default");
	core::require(maxSlidingExact >= 0, "ImplicitLogTimeSolver.maxSlidingExact", maxSlidingExact, ">= 0");
	core::require(kinkPasses >= 0, "ImplicitLogTimeSolver.kinkPasses", kinkPasses, ">= 0 (0: never)");
	core::require(lowRankChanges >= 0, "ImplicitLogTimeSolver.lowRankChanges", lowRankChanges, ">= 0");
	core::requireOpenInterval("ImplicitLogTimeSolver.relaxTolerance", relaxTolerance, 0, 1);
	core::require(stallTolerance >= 0 && stallTolerance < 1, "ImplicitLogTimeSolver.stallTolerance", stallTolerance, "0 <= stallTolerance < 1");
	core::require(fallbackIterations >= 0, "ImplicitLogTimeSolver.fallbackIterations", fallbackIterations, ">= 0 (0: never)");
	core::requireOpenInterval("ImplicitLogTimeSolver.fallbackTolerance", fallbackTolerance, 0, 1);
	// PETSc counts iterations in a 32-bit int
	core::require(gmresLimit >= 1 && gmresLimit <= (1L << 30), "ImplicitLogTimeSolver.gmresLimit", gmresLimit, "1 <= gmresLimit <= 1073741824");
	core::require(autoFactorMemoryShare > 0, "ImplicitLogTimeSolver.autoFactorMemoryShare", autoFactorMemoryShare, "> 0");
	if (linearSolver != "auto" && linearSolver != "cholmod" && linearSolver != "petsc-gamg" && linearSolver != "petsc-mumps")
		throw std::invalid_argument("ImplicitLogTimeSolver.linearSolver = '" + linearSolver
		                            + "' is not a linear solver; allowed: auto, cholmod, petsc-gamg, petsc-mumps");
	if (linearSolver.rfind("petsc-", 0) == 0) {
		const std::string why = swelldem::linalg::petscUnavailable();
		if (!why.empty()) throw std::invalid_argument("ImplicitLogTimeSolver.linearSolver = '" + linearSolver + "': " + why);
	}
}

string ImplicitLogTimeSolver::fallbackDetail() const
{
	char buf[200];
	std::snprintf(buf, sizeof buf, "%.0e (handed over at ratio %.2e after %ld iterations of the round, %d contacts changing state)",
	              double(std::max(tolerance, fallbackTolerance)), double(fallbackRatio.empty() ? 0.0 : fallbackRatio.back()), fallbackIterations,
	              fallbackChanging.empty() ? 0 : fallbackChanging.back());
	return buf;
}

const unsigned* ImplicitLogTimeSolver::dofBits() const
{
	static const unsigned bits2D[3] = { State::DOF_X, State::DOF_Y, State::DOF_RZ };
	static const unsigned bits3D[6] = { State::DOF_X, State::DOF_Y, State::DOF_Z, State::DOF_RX, State::DOF_RY, State::DOF_RZ };
	return nDim == 3 ? bits3D : bits2D;
}

void ImplicitLogTimeSolver::choosePins()
{
	// A specimen held nowhere in translation has rigid-body modes (2D: two translations, one
	// rotation; 3D: three and three), which make K singular. They are removed by holding one body
	// near the centre in every translation and, in 2D, a second, far from it, across the line
	// joining them: this moves the specimen as a rigid body only, so no force and no strain changes
	// (tests/python/test_implicit_solver.py). In 3D the centre body's rotations are held
	// instead of other bodies' positions: a rigid rotation turns every body, so this removes the
	// three rotation modes too, and it turns the specimen only by that body's own rotation, not by
	// the specimen's strain across a line (YADE's 3D shear is not exactly objective: a free swelling
	// lattice turned by its strain, 1.8e-3 rad, carried self-balanced forces of 7e-5 of its
	// swelling force; not turned, 1e-12: tests/python/test_implicit_3d.py).
	pinnedDofs.assign(1, -1); // decided: none
	const auto&    bodies = scene->bodies->body;
	const bool     threeD = nDim == 3;
	const int      nd     = threeD ? 3 : 2;
	const auto&    L      = scene->interactions->linIntrs;
	// 3D: an axis is held when a held body pushes along it through a contact (a platen's normal; its
	// shear is next to nothing, so z platens leave x and y free), and a rotation about an axis when
	// some other axis is held; the centre sphere is held in what is left.
	bool held[3] = { false, false, false };
	if (threeD) {
		for (size_t i = 0; i < scene->interactions->currSize; ++i) {
			const Interaction* I = L[i].get();
			if (!I->isReal()) continue;
			const Vector3r& n = static_cast<const ScGeom*>(I->geom.get())->normal;
			for (int id : { I->id1, I->id2 })
				for (int d = 0; d < 3; ++d)
					if ((bodies[id]->state->blockedDOFs & kAxisDOF[d]) && std::abs(n[d]) > 0.5) held[d] = true;
		}
		if (held[0] && held[1] && held[2]) return;
	} else {
		for (const auto& b : bodies)
			if (b && (b->state->blockedDOFs & (State::DOF_X | State::DOF_Y))) return;
	}
	std::vector<int> degree(bodies.size(), 0);
	for (size_t i = 0; i < scene->interactions->currSize; ++i)
		if (L[i]->isReal()) ++degree[L[i]->id1], ++degree[L[i]->id2];
	auto     pos = [&](int id) { return bodies[id]->state->se3.position; };
	Vector3r c   = Vector3r::Zero();
	long     n   = 0;
	for (const auto& b : bodies)
		if (b && degree[b->id] >= 2) c.head(nd) += pos(b->id).head(nd), ++n;
	if (n < 2) return;
	c /= Real(n);
	int  a = -1, f = -1;
	Real best = std::numeric_limits<Real>::infinity(), far = -1;
	for (const auto& b : bodies)
		if (b && degree[b->id] >= 2) {
			const Real d = (pos(b->id).head(nd) - c.head(nd)).norm();
			if (d < best) best = d, a = b->id;
		}
	if (threeD) {
		pinnedDofs.clear();
		for (int d = 0; d < 3; ++d)
			if (!held[d]) pinnedDofs.push_back(6 * a + d);
		for (int k = 0; k < 3; ++k)
			if (!held[(k + 1) % 3] && !held[(k + 2) % 3]) pinnedDofs.push_back(6 * a + 3 + k);
		return;
	}
	for (const auto& b : bodies)
		if (b && degree[b->id] >= 2) {
			const Real d = (pos(b->id).head(nd) - pos(a).head(nd)).norm();
			if (d > far) far = d, f = b->id;
		}
	const Vector2r d = bodies[f]->state->se3.position.head<2>() - bodies[a]->state->se3.position.head<2>();
	pinnedDofs       = { 3 * a, 3 * a + 1, 3 * f + (std::abs(d[0]) >= std::abs(d[1]) ? 1 : 0) };
}

double ImplicitLogTimeSolver::factorPeakBytes(double entries)
{
	// CHOLMOD's supernodal factorization at its peak: 8 bytes an entry of L and its indices and
	// workspace (FCC lattice of 74,439 spheres, 6.1e8 entries: 4.9 GB for L, 7 GB peak)
	return 11.5 * entries;
}

double ImplicitLogTimeSolver::physicalMemoryBytes()
{
	const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
	return pages > 0 && size > 0 ? double(pages) * double(size) : 0.0;
}

void ImplicitLogTimeSolver::numberEquations()
{
	// Equation numbering and sparsity pattern, remade when the contact graph or the held DOFs change.
	if (pinnedDofs.empty()) choosePins();
	const std::vector<unsigned> masks = heldDofMasks();
	if (sameEquations(masks)) return;
	numberDofs(masks);
	makePattern();
	findSlots();
	// auto decides once a run, on its first system, so that a run does not change solver as its
	// contacts break: CHOLMOD wherever its factor fits (on whole 3D damage runs it is the faster of
	// the two at every size measured, docs/performance.md section 7), GAMG where the factor's
	// peak would pass autoFactorMemoryShare of the memory, and on MPI ranks, which only PETSc uses.
	// A 2D factor's fill grows as N log N and stays small.
	const bool choosing = linearSolver == "auto" && linearSolverUsed.empty(), petscThere = swelldem::linalg::petscUnavailable().empty();
	if (linearSolver != "auto") linearSolverUsed = linearSolver;
	else if (choosing) linearSolverUsed = swelldem::linalg::mpiRanks() > 1 && petscThere ? "petsc-gamg" : "cholmod";
	if (linearSolverUsed == "cholmod") {
		sys->petsc.reset();
		sys->chol.setMode(Eigen::CholmodSupernodalLLt);
		sys->chol.analyzePattern(sys->K);
		factorNonZeros = sys->chol.cholmod().lnz;
		const double peak = factorPeakBytes(factorNonZeros), memory = physicalMemoryBytes();
		if (choosing && sys->nb == 6 && petscThere && memory > 0 && peak > autoFactorMemoryShare * memory) {
			linearSolverUsed = "petsc-gamg";
			if (verbose) {
				std::printf("swelldem: linearSolver auto: CHOLMOD's factor of these %d equations would hold %.3g entries, %.1f GB at its "
				            "peak, more than %.0f %% of the machine's %.1f GB (autoFactorMemoryShare): petsc-gamg\n",
				            sys->nEq, double(factorNonZeros), peak / 1e9, 100 * autoFactorMemoryShare, memory / 1e9);
				std::fflush(stdout);
			}
		}
	}
	if (linearSolverUsed != "cholmod") openLinearSolver(), factorNonZeros = 0;
	refactorSavedValues();
	sys->active.assign(sys->contacts.size(), 0);
	++analyses;
}

std::vector<unsigned> ImplicitLogTimeSolver::heldDofMasks() const
{
	const auto&           bodies = scene->bodies->body;
	const unsigned        dofs   = nDim == 3 ? kAllDOF : State::DOF_X | State::DOF_Y | State::DOF_RZ;
	std::vector<unsigned> masks(bodies.size(), 0);
	for (const auto& b : bodies)
		if (b) masks[b->id] = b->state->blockedDOFs & dofs;
	return masks;
}

bool ImplicitLogTimeSolver::sameEquations(const std::vector<unsigned>& masks) const
{
	const ImplicitLinearSystem& S        = *sys;
	const auto&                 contacts = S.contacts;
	bool                        same     = masks == S.dofMasks && contacts.size() == S.graph.size();
	for (size_t c = 0; same && c < contacts.size(); ++c)
		same = S.graph[c].first == contacts[c]->id1 && S.graph[c].second == contacts[c]->id2;
	return same;
}

void ImplicitLogTimeSolver::numberDofs(const std::vector<unsigned>& masks)
{
	// The pins are taken out after a first numbering, so that the equations keep the bodies' order.
	ImplicitLinearSystem& S      = *sys;
	const auto&           bodies = scene->bodies->body;
	S.dofMasks                   = masks;
	S.nb                         = dofsPerBody();
	S.pairs                      = S.nb == 6 ? &kPairs3D : &kPairs2D;
	const int nb                 = S.nb;
	S.dofOf.assign(nb * bodies.size(), -1);
	S.nEq = 0;
	const unsigned* axisBit = dofBits();
	for (const auto& b : bodies)
		if (b && !b->isClump())
			for (int d = 0; d < nb; ++d)
				if (!(masks[b->id] & axisBit[d])) S.dofOf[nb * b->id + d] = S.nEq++;
	for (int p : pinnedDofs)
		if (p >= 0 && size_t(p) < S.dofOf.size()) S.dofOf[p] = -1;
	S.nEq = 0; // renumber without the pins
	S.isRotation.clear();
	for (size_t k = 0; k < S.dofOf.size(); ++k)
		if (S.dofOf[k] >= 0) S.dofOf[k] = S.nEq++, S.isRotation.push_back(int(k % nb) >= (nb == 6 ? 3 : 2));
}

void ImplicitLogTimeSolver::makePattern()
{
	// Every diagonal entry is in the pattern, so that a DOF no contact holds can take kLoose.
	ImplicitLinearSystem& S        = *sys;
	const auto&           contacts = S.contacts;
	S.graph.resize(contacts.size());
	const PairTable&                         P = *S.pairs;
	std::vector<Eigen::Triplet<double, int>> trip;
	trip.reserve(contacts.size() * P.size + S.nEq);
	for (int e = 0; e < S.nEq; ++e)
		trip.emplace_back(e, e, 0.0);
	for (size_t c = 0; c < contacts.size(); ++c) {
		const Interaction* I = contacts[c];
		S.graph[c]           = { I->id1, I->id2 };
		int eq[LowRankColumn::kSize];
		S.equationsOf(I, eq);
		for (int k = 0; k < P.size; ++k) {
			const int r = eq[P.a[k]], s = eq[P.b[k]];
			if (r >= 0 && s >= 0) trip.emplace_back(std::max(r, s), std::min(r, s), 0.0);
		}
	}
	S.K.resize(S.nEq, S.nEq);
	S.K.setFromTriplets(trip.begin(), trip.end());
	S.K.makeCompressed();
}

void ImplicitLogTimeSolver::findSlots()
{
	// Found once per pattern, so that assembling the tangent writes K's values without a search.
	ImplicitLinearSystem& S        = *sys;
	const auto&           contacts = S.contacts;
	const PairTable&      P        = *S.pairs;
	S.slots.assign(P.size * contacts.size(), -1);
	S.diagSlot.assign(S.nEq, -1);
	for (int e = 0; e < S.nEq; ++e)
		S.diagSlot[e] = S.slotOf(e, e);
	for (size_t c = 0; c < contacts.size(); ++c) {
		int eq[LowRankColumn::kSize];
		S.equationsOf(contacts[c], eq);
		for (int k = 0; k < P.size; ++k) {
			const int r = eq[P.a[k]], s = eq[P.b[k]];
			if (r >= 0 && s >= 0) S.slots[P.size * c + k] = S.slotOf(std::max(r, s), std::min(r, s));
		}
	}
}

void ImplicitLogTimeSolver::refactorSavedValues()
{
	// A reloaded scene factors the values the saved run had factored, if its contacts are the same,
	// so that it keeps or renews its factor exactly as the uninterrupted run.
	ImplicitLinearSystem& S = *sys;
	std::vector<int>      graph;
	graph.reserve(2 * S.contacts.size());
	for (const Interaction* I : S.contacts)
		graph.push_back(I->id1), graph.push_back(I->id2);
	S.haveFactor = false;
	if (graph == factoredGraph && factoredValues.size() == size_t(S.K.nonZeros())) {
		const Eigen::VectorXd current = Eigen::Map<const Eigen::VectorXd>(S.K.valuePtr(), S.K.nonZeros());
		std::copy(factoredValues.begin(), factoredValues.end(), S.K.valuePtr());
		S.haveFactor = factorValues();
		std::copy(current.data(), current.data() + current.size(), S.K.valuePtr());
	} else
		factoredValues.clear(), factoredStiffness.clear(), factoredDrift.clear(), factoredAcross.clear();
	factoredGraph.swap(graph);
}

void ImplicitLogTimeSolver::assembleTangent(bool firstPass, bool exact)
{
	// K = sum over contacts of B^T diag(kn, ks) B with, over (x1, y1, rz1, x2, y2, rz2), normal row
	// (-n, 0, n, 0) and shear row (-t, -r1, t, -r2), t = ez x n (the increments YADE's ScGeom gives
	// the law). Unless exact, a contact whose (kn, ks) changed since the factor was made enters with
	// its factored ones, and the change as low-rank columns.
	ImplicitLinearSystem& S = *sys;
	startAssembly();
	const bool lowRank = !exact && S.haveFactor && factoredStiffness.size() == 2 * S.contacts.size();
	long       changes = 0;
	double     kScale  = 0; // mean step stiffness kn'' of the contacts
	for (size_t c = 0; c < S.contacts.size(); ++c) {
		kScale += std::abs(static_cast<const NormShearPhys*>(S.contacts[c]->phys.get())->kn);
		const char state = addContact(c, lowRank);
		if (firstPass) changes += state != S.active[c], S.active[c] = state;
	}
	if (firstPass) activeChanges = changes;
	double* v = S.K.valuePtr();
	forEachSpring([&](int id, int axis, Real k) {
		const int e = S.dofOf[S.nb * id + axis];
		if (e >= 0) v[S.diagSlot[e]] += k;
	});
	kScale            = S.contacts.empty() ? 1.0 : kScale / S.contacts.size();
	const Real kLoose = kScale > 0 ? kScale : 1.0;
	std::vector<Real> raw(S.touched.size()); // the changed contacts' diagonal entries before the shifts
	for (size_t i = 0; i < S.touched.size(); ++i)
		raw[i] = v[S.diagSlot[S.touched[i]]];
	shiftDiagonal(kLoose);
	addDiagonalColumns(raw, kLoose);
}

void ImplicitLogTimeSolver::startAssembly()
{
	ImplicitLinearSystem& S = *sys;
	double*               v = S.K.valuePtr();
	std::fill(v, v + S.K.nonZeros(), 0.0);
	S.acrossInK = false;
	S.deltaDiag.assign(S.nEq, 0.0);
	S.touched.clear();
	S.columns.clear();
	S.across.clear();
	S.stiffness.resize(2 * S.contacts.size());
	S.changed = 0;
}

char ImplicitLogTimeSolver::addContact(size_t c, bool lowRank)
{
	// A sliding contact of a disc in a mechanism enters as sticking. A contact carrying nothing in
	// K nor in a column is left out. Returns the contact's state (core::ContactLaw::Mode).
	ImplicitLinearSystem& S = *sys;
	const Interaction*    I = S.contacts[c];
	Real                  kn, ks, slide, dir[3];
	const char state = contactTangent(*law2, I, kn, ks, slide, dir, S.mech[I->id1] || S.mech[I->id2], !S.kink.empty() && S.kink[c]);
	S.stiffness[2 * c] = kn, S.stiffness[2 * c + 1] = ks;
	Real kA = kn, sA = ks; // into K
	const bool changedHere = lowRank && (kn != factoredStiffness[2 * c] || ks != factoredStiffness[2 * c + 1]);
	if (kn == 0 && ks == 0 && !changedHere) return state;
	Real      bn[12], bs[12], bs2[12];
	const int nc = contactRows(I, S.nb, bn, bs, bs2);
	if (changedHere) addStiffnessChange(c, kn, ks, bn, bs, bs2, kA, sA);
	if (slide != 0 && nc == 6) S.addColumn(I, 2, slide, bs, bn);
	if (slide != 0 && nc == 12) {
		Real along[12]; // the slip along the shear force
		for (int k = 0; k < 12; ++k)
			along[k] = dir[0] * bs[k] + dir[1] * bs2[k];
		S.addColumn(I, 2, slide, along, bn);
	}
	const PairTable& P    = *S.pairs;
	const int*       slot = &S.slots[P.size * c];
	double*          v    = S.K.valuePtr();
	if (nc == 6) {
		for (int k = 0; k < P.size; ++k)
			if (slot[k] >= 0) v[slot[k]] += kA * bn[P.a[k]] * bn[P.b[k]] + sA * bs[P.a[k]] * bs[P.b[k]];
	} else
		for (int k = 0; k < P.size; ++k)
			if (slot[k] >= 0) v[slot[k]] += kA * bn[P.a[k]] * bn[P.b[k]] + sA * (bs[P.a[k]] * bs[P.b[k]] + bs2[P.a[k]] * bs2[P.b[k]]);
	if (dir[2] > 0) S.across.push_back({ Real(c), dir[0], dir[1], dir[2] });
	return state;
}

void ImplicitLogTimeSolver::addStiffnessChange(size_t c, Real kn, Real ks, const Real* bn, const Real* bs, const Real* bs2, Real& kA, Real& sA)
{
	// The factor stays valid for K with the factored (kA, sA); the change enters the solve exactly, as
	// columns, and its diagonal is kept for the shifts' correction (addDiagonalColumns).
	ImplicitLinearSystem& S = *sys;
	const Interaction*    I = S.contacts[c];
	++S.changed;
	const Real dkn = kn - factoredStiffness[2 * c], dks = ks - factoredStiffness[2 * c + 1];
	const bool            threeD = S.nb == 6;
	if (dkn != 0) S.addColumn(I, 0, dkn, bn, bn), kA = factoredStiffness[2 * c];
	if (dks != 0) S.addColumn(I, 1, dks, bs, bs), sA = factoredStiffness[2 * c + 1];
	if (dks != 0 && threeD) S.addColumn(I, 4, dks, bs2, bs2);
	int eq[LowRankColumn::kSize];
	S.equationsOf(I, eq);
	for (int k = 0; k < S.nc(); ++k)
		if (eq[k] >= 0) {
			if (S.deltaDiag[eq[k]] == 0) S.touched.push_back(eq[k]);
			S.deltaDiag[eq[k]] += dkn * bn[k] * bn[k] + dks * bs[k] * bs[k] + (threeD ? dks * bs2[k] * bs2[k] : 0.0);
		}
}

void ImplicitLogTimeSolver::shiftDiagonal(Real kLoose)
{
	ImplicitLinearSystem& S = *sys;
	double*               v = S.K.valuePtr();
	// A DOF that no contact holds in the current state (a loose disc, a disc whose contacts are all
	// open) moves under its own load as if one typical contact held it, so that it can close them.
	for (int e = 0; e < S.nEq; ++e) {
		double& d = v[S.diagSlot[e]];
		d += d > 0 ? regularization * d : kLoose;
	}
	// A disc held by one contact can roll about it: a mode of zero stiffness in this tangent, along
	// which a torque residual at round-off would move it without bound (measured: with a factor 3e-6
	// off the tangent, one move of a 20 mm specimen without damage grew its residual 3e4-fold). The
	// shift bounds that move; rotations converge by this factor an iteration, and YADE's shear,
	// integrated along their path, ends within about the shift of the exact path's (free lattice:
	// 4.5e-8 of the opening at 1e-3, 8e-13 without). The shift is taken of the disc's own diagonal,
	// at most of the median disc's: a stiff aggregate turns as a whole inside a soft matrix, held by
	// the matrix alone, and a shift of its own discs' diagonals would be of the order of that hold
	// (measured at an aggregate modulus 1000 x the paper's: Newton converged by 0.8 an iteration and
	// never settled a cracking step that the ADR settles).
	std::vector<double> rot;
	rot.reserve(S.nEq / 3 + 1);
	for (int e = 0; e < S.nEq; ++e)
		if (S.isRotation[e]) rot.push_back(v[S.diagSlot[e]]);
	S.rotationScale = 0;
	if (!rot.empty()) {
		std::nth_element(rot.begin(), rot.begin() + rot.size() / 2, rot.end());
		S.rotationScale = rot[rot.size() / 2];
	}
	for (int e = 0; e < S.nEq; ++e)
		if (S.isRotation[e]) v[S.diagSlot[e]] += rotationShift(v[S.diagSlot[e]]);
}

// A sphere's rotations are held by about twelve contacts, a disc's by four to six: in 3D the shift
// that bounds a rolling mode slows the rotations' convergence more than it saves in mechanisms
// (12 mm ISR cube, damage: 1e-3 made the steps after the first breaks converge by 0.68 an
// iteration; 1e-5 took 542 Newton iterations in all against 883), in 2D the other way round.
Real ImplicitLogTimeSolver::rotationShiftFactor() const
{
	if (rotationRegularization >= 0) return rotationRegularization;
	// GAMG's coarse space holds the rigid-body modes only: a sphere's rotation that its few contacts
	// leave nearly free is an eigenvalue of the shift's size that CG must find on its own (the 40 mm
	// cube's first solve stagnates at a relative 1e-3 at 1e-5, converges in 34 iterations at 1e-3)
	if (nDim == 3) return linearSolverUsed == "petsc-gamg" ? 1e-3 : 1e-5;
	return 1e-3;
}

long ImplicitLogTimeSolver::changingLimitOfDimension() const { return changingLimit >= 0 ? changingLimit : (nDim == 3 ? 2 : 0); }

Real ImplicitLogTimeSolver::rotationShift(Real diagonal) const { return rotationShiftFactor() * std::min(diagonal, Real(sys->rotationScale)); }

void ImplicitLogTimeSolver::addDiagonalColumns(const std::vector<Real>& raw, Real kLoose)
{
	// The diagonal shifts act on the whole diagonal, which the changes' columns do not see: a DOF
	// whose changes leave it held by nothing (its last contact opened) has kScale in the exact
	// tangent, not the factored stiffness minus the change, and one that a change holds again loses
	// its kScale. A diagonal column brings J to the exact entry where the two differ by more than
	// 1 % (without it J is singular, or far too stiff, along that DOF, and Newton stalls).
	ImplicitLinearSystem& S = *sys;
	const double*         v = S.K.valuePtr();
	for (size_t i = 0; i < S.touched.size(); ++i) {
		const int  e     = S.touched[i];
		const Real d     = raw[i] + S.deltaDiag[e];
		const Real held  = d > 1e-9 * std::abs(raw[i]) ? d * (1 + regularization) : d + kLoose;
		const Real exact = held + (S.isRotation[e] ? rotationShift(held) : 0.0);
		const Real lowRankEntry = v[S.diagSlot[e]] + S.deltaDiag[e];
		if (!(std::abs(exact - lowRankEntry) > 1e-2 * std::abs(exact))) continue;
		LowRankColumn col { -1 - e, -1, 3, exact - lowRankEntry, {}, {}, {} };
		std::fill(col.eq, col.eq + LowRankColumn::kSize, -1);
		col.eq[0] = e, col.u[0] = col.value, col.v[0] = 1;
		S.columns.push_back(col);
	}
}

bool ImplicitLogTimeSolver::needsFactor(bool freshFactor) const
{
	// Factor when the tangent changed: a new step of an aging kind, a break, more than lowRankChanges
	// contacts changing state, a mechanism held. The geometry moving within a step changes the
	// entries by about the strain increment (1e-5 to 1e-4 of the largest): the factor is kept, and the
	// iteration is a modified Newton step on YADE's exact residual. Every step starts with a fresh
	// factor (freshFactor), so that the drift a factor carries is one step's strain, never the run's.
	const ImplicitLinearSystem& S   = *sys;
	const double*               v   = S.K.valuePtr();
	const long                  nnz = S.K.nonZeros();
	if (!S.haveFactor || factoredValues.size() != size_t(nnz) || freshFactor || S.changed > lowRankChanges) return true;
	// A 3D sliding contact's stiffness across its slip, ks |Fs| / |Fs trial|, falls as its slip grows
	// within the step; factored at a stiffer value, it makes the move across the slip too short and
	// Newton converges by 1 - (its value) / (the factored one) an iteration (measured: 0.95 in the
	// late steps of a 12 mm ISR cube, which stalled at newtonLimit). Down to half the factored
	// value that rate stays under 1/2; above it a move overshoots by (its value) / (the factored
	// one) - 1, which must stay under 1: refactored outside [1/2, 2] x the factored value.
	if (factoredAcross.size() == S.contacts.size())
		for (const auto& a : S.across) {
			const Real was = factoredAcross[size_t(a[0])];
			if (was > 0 && (a[3] < 0.5 * was || a[3] > 2 * was)) return true;
		}
	const std::vector<Real>& ref = factoredDrift.size() == size_t(nnz) ? factoredDrift : factoredValues;
	double                   drift = 0, largest = 0;
	for (long k = 0; k < nnz; ++k)
		drift = std::max(drift, std::abs(v[k] - ref[k])), largest = std::max(largest, std::abs(v[k]));
	return !(drift <= refactorTolerance * largest);
}

void ImplicitLogTimeSolver::factor()
{
	ImplicitLinearSystem& S = *sys;
	// A 3D sliding contact's stiffness across its slip changes at every iteration while it slides
	// (the trial shear turns): it enters the factor made now, and its later changes enter no new
	// one (the drift is measured without it: factoredDrift), as the geometry's drift does not. In K's
	// values at every iteration it made the 12 mm ISR run refactor 153 times, against 62 without it
	// in the tangent at all, where Newton stalled after the first breaks (3,103 iterations against 1,137).
	if (!S.across.empty()) {
		factoredDrift.assign(S.K.valuePtr(), S.K.valuePtr() + S.K.nonZeros());
		addAcross(S, S.K.valuePtr());
		factoredAcross.assign(S.contacts.size(), 0.0);
		for (const auto& a : S.across)
			factoredAcross[size_t(a[0])] = a[3];
	} else if (!factoredDrift.empty())
		factoredDrift.clear(), factoredAcross.clear();
	S.acrossInK     = !S.across.empty();
	const auto start = std::chrono::steady_clock::now();
	const bool ok    = factorValues();
	factorSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
	++factorizations;
	if (!ok)
		fail("the tangent stiffness (" + std::to_string(S.nEq) + " equations) is not positive definite; " + linearSolverUsed
		     + " could not factor it");
	factoredValues.assign(S.K.valuePtr(), S.K.valuePtr() + S.K.nonZeros());
	factoredStiffness = S.stiffness;
	S.haveFactor      = true;
	S.z.clear();
	lowRankColumns.clear();
}

Eigen::VectorXd ImplicitLogTimeSolver::solveWithCoupling(const Eigen::VectorXd& r)
{
	// J = K_f + U V^T is solved with K_f's Cholesky factor and the Sherman-Morrison-Woodbury formula.
	// Its columns: the state changes since the factor was made (at most lowRankChanges contacts, a
	// solve each instead of a factorization) and the sliding contacts' shear-normal coupling, which
	// makes the tangent unsymmetric (without it Newton converges only linearly, at rates up to 0.98
	// an iteration, measured on 20 mm ISR cracking); the coupling is left out above maxSlidingExact
	// sliding contacts.
	ImplicitLinearSystem& S        = *sys;
	long                  nSliding = 0;
	for (const auto& col : S.columns)
		nSliding += col.type == 2;
	std::vector<const LowRankColumn*> use;
	for (const auto& col : S.columns)
		if (col.type != 2 || nSliding <= maxSlidingExact) use.push_back(&col);
	if (S.petsc && S.petsc->iterative()) return krylovSolve(r, use);
	Eigen::VectorXd du = directSolve(r);
	if (use.empty()) return du;
	// z = K_f^-1 u costs a solve. A column's z is kept with the factor, for the same contact, type
	// and value (the u of its first iteration: the geometry's drift enters as the factor's does),
	// and saved, so that a reloaded scene rebuilds the same z; factor() empties them.
	std::vector<size_t> pending; // columns whose z is (re)solved in this call
	auto                solvePending = [&]() {
		S.z.resize(lowRankColumns.size());
		auto columnOf = [&](size_t j, auto&& u) {
			const LowRankColumn& col = lowRankColumns[j];
			for (int k = 0; k < S.nc(); ++k)
				if (col.eq[k] >= 0) u[col.eq[k]] += col.u[k];
		};
		if (S.nb == 3) {
			// a section's cracking step has tens of new columns and a disc's factor solves fast:
			// one solve each, whose results the sections' runs have always had
			for (size_t j : pending) {
				Eigen::VectorXd u = Eigen::VectorXd::Zero(S.nEq);
				columnOf(j, u);
				S.z[j] = directSolve(u);
			}
		} else {
			// A 3D cracking round has hundreds of sliding contacts' columns, and one solve of a
			// 3D factor reads all of it from memory (20 mm cube: 42 % of a run in single
			// solves): blocks of columns are solved together, CHOLMOD's supernodal solve then
			// reads the factor once a block with BLAS-3 kernels. A block has at least two
			// columns (a zero beside a single one) so that every z comes from the same kernels,
			// each column's arithmetic independent of its neighbours: a reloaded scene's
			// blocks rebuild the same z.
			constexpr size_t block = 32;
			for (size_t first = 0; first < pending.size(); first += block) {
				const size_t    n = std::min(block, pending.size() - first);
				Eigen::MatrixXd U = Eigen::MatrixXd::Zero(S.nEq, long(std::max<size_t>(n, 2)));
				for (size_t i = 0; i < n; ++i)
					columnOf(pending[first + i], U.col(long(i)));
				const Eigen::MatrixXd Z = directSolve(U);
				for (size_t i = 0; i < n; ++i)
					S.z[pending[first + i]] = Z.col(long(i));
			}
		}
		pending.clear();
	};
	for (size_t j = S.z.size(); j < lowRankColumns.size(); ++j)
		pending.push_back(j); // a reloaded scene
	solvePending();
	std::map<std::tuple<int, int, int, Real>, size_t> kept;
	for (size_t j = 0; j < S.z.size(); ++j)
		kept.emplace(std::make_tuple(lowRankColumns[j].id1, lowRankColumns[j].id2, lowRankColumns[j].type, lowRankColumns[j].value), j);
	std::vector<size_t> index(use.size());
	for (size_t i = 0; i < use.size(); ++i) {
		const auto& col = *use[i];
		const auto  it  = kept.find(std::make_tuple(col.id1, col.id2, col.type, col.value));
		if (it != kept.end()) {
			// kept while its u is within refactorTolerance of the one it was solved for, as the factor.
			// A 3D sliding contact's coupling turns with its shear force at every iteration: kept
			// within 10 % (about 6 degrees), a modified tangent like a kept factor (12 mm cube, ISR,
			// 2 steps a decade: 35 s and 791 iterations, against 49 s re-solving it at every turn and
			// 30 s but 983 iterations without the coupling at all).
			const size_t j     = index[i] = it->second;
			const Real   keep  = col.type == 2 && S.nb == 6 ? std::max(refactorTolerance, Real(0.1)) : refactorTolerance;
			Real         drift = 0, size = 0;
			for (int k = 0; k < S.nc(); ++k)
				drift = std::max(drift, std::abs(col.u[k] - lowRankColumns[j].u[k])), size = std::max(size, std::abs(col.u[k]));
			if (!(drift > keep * size)) continue;
			std::copy(col.u, col.u + LowRankColumn::kSize, lowRankColumns[j].u);
			pending.push_back(j);
			continue;
		}
		index[i] = lowRankColumns.size();
		pending.push_back(lowRankColumns.size());
		lowRankColumns.push_back(col);
	}
	solvePending();
	const long m    = long(use.size());
	auto vDot = [nc = S.nc()](const LowRankColumn& col, const Eigen::VectorXd& x) {
		Real s = 0;
		for (int k = 0; k < nc; ++k)
			if (col.eq[k] >= 0) s += col.v[k] * x[col.eq[k]];
		return s;
	};
	Eigen::MatrixXd Sm = Eigen::MatrixXd::Identity(m, m);
	Eigen::VectorXd vy(m);
	for (long i = 0; i < m; ++i) {
		vy[i] = vDot(*use[i], du);
		for (long j = 0; j < m; ++j)
			Sm(i, j) += vDot(*use[i], S.z[index[j]]);
	}
	const Eigen::VectorXd y = Sm.partialPivLu().solve(vy);
	for (long j = 0; j < m; ++j)
		du -= y[j] * S.z[index[j]];
	return du;
}

long ImplicitLogTimeSolver::holdMechanisms(const Eigen::VectorXd& du)
{
	// A mechanism shows as a relative move across a contact far beyond elastic ones (measured: 10 to
	// 300 radii where a disc's contacts all slide, against 1e-3 radii in elastic steps). Both discs'
	// sliding contacts then enter the tangent as sticking, and the move is solved again.
	ImplicitLinearSystem& S = *sys;
	if (mechanismMove == 0) return 0;
	long newlyHeld = 0;
	auto moveOf    = [&](int id, int d) {
		const int e = S.dofOf[S.nb * id + d];
		return e >= 0 ? du[e] : 0.0;
	};
	auto turnOf = [&](int id) { return Vector3r(moveOf(id, 3), moveOf(id, 4), moveOf(id, 5)).norm(); };
	for (const Interaction* I : S.contacts) {
		const auto* g = static_cast<const ScGeom*>(I->geom.get());
		const Real  rel =
		        S.nb == 3 ? std::hypot(moveOf(I->id2, 0) - moveOf(I->id1, 0), moveOf(I->id2, 1) - moveOf(I->id1, 1))
		                        + std::abs(moveOf(I->id1, 2)) * g->radius1 + std::abs(moveOf(I->id2, 2)) * g->radius2
		                  : Vector3r(moveOf(I->id2, 0) - moveOf(I->id1, 0), moveOf(I->id2, 1) - moveOf(I->id1, 1), moveOf(I->id2, 2) - moveOf(I->id1, 2)).norm()
		                        + turnOf(I->id1) * g->radius1 + turnOf(I->id2) * g->radius2;
		if (!(rel > mechanismMove * 0.5 * (g->radius1 + g->radius2))) continue;
		for (int id : { I->id1, I->id2 })
			if (!S.mech[id]) S.mech[id] = 1, heldMechanisms.push_back(id), ++newlyHeld, ++mechanismHolds;
	}
	return newlyHeld;
}

namespace {
	// The LCP w = A s + q >= 0, s >= 0, s.w = 0 by block principal pivoting (Judice and Pires):
	// every index infeasible in the current basis changes side at once while that lowers their
	// count, and, after three pivots that did not, the largest such index alone (Murty's rule),
	// which ends for a P-matrix A (every principal minor positive). Returns false if it has not
	// ended within maxPivots.
	bool solveLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& q, Eigen::VectorXd& s, int maxPivots)
	{
		const long        m = q.size();
		std::vector<char> basic(m, 0); // s_i free (w_i = 0), else s_i = 0
		long              fewest = m + 1;
		int               backup = 3;
		for (int pivot = 0; pivot <= maxPivots; ++pivot) {
			std::vector<long> B;
			for (long i = 0; i < m; ++i)
				if (basic[i]) B.push_back(i);
			s.setZero(m);
			if (!B.empty()) {
				Eigen::MatrixXd AB(B.size(), B.size());
				Eigen::VectorXd qB(B.size());
				for (size_t a = 0; a < B.size(); ++a) {
					qB[a] = -q[B[a]];
					for (size_t b = 0; b < B.size(); ++b)
						AB(a, b) = A(B[a], B[b]);
				}
				const Eigen::VectorXd sB = AB.partialPivLu().solve(qB);
				if (!sB.allFinite()) return false;
				for (size_t a = 0; a < B.size(); ++a)
					s[B[a]] = sB[a];
			}
			const Eigen::VectorXd w = A * s + q;
			std::vector<long>     bad;
			for (long i = 0; i < m; ++i)
				if (basic[i] ? s[i] < 0 : w[i] < 0) bad.push_back(i);
			if (bad.empty()) return true;
			if (long(bad.size()) < fewest)
				fewest = long(bad.size()), backup = 3;
			else if (backup > 0)
				--backup;
			else {
				basic[bad.back()] = !basic[bad.back()];
				continue;
			}
			for (long i : bad)
				basic[i] = !basic[i];
		}
		return false;
	}
}

Real ImplicitLogTimeSolver::kinkOpening(const Interaction* I, const Eigen::VectorXd& x) const
{
	const ImplicitLinearSystem& S = *sys;
	const Vector3r&             n = static_cast<const ScGeom*>(I->geom.get())->normal;
	auto                        m = [&](int id, int d) {
                const int e = S.dofOf[S.nb * id + d];
                return e >= 0 ? x[e] : 0.0;
	};
	const Real open = n[0] * (m(I->id2, 0) - m(I->id1, 0)) + n[1] * (m(I->id2, 1) - m(I->id1, 1));
	return S.nb == 3 ? open : open + n[2] * (m(I->id2, 2) - m(I->id1, 2));
}

void ImplicitLogTimeSolver::addNormalRow(const Interaction* I, Real scale, Eigen::VectorXd& v) const
{
	int eq[LowRankColumn::kSize];
	sys->equationsOf(I, eq);
	Real      bn[12], bs[12], bs2[12];
	const int nc = contactRows(I, sys->nb, bn, bs, bs2);
	for (int k = 0; k < nc; ++k)
		if (eq[k] >= 0) v[eq[k]] += scale * bn[k];
}

bool ImplicitLogTimeSolver::kinkModel(const std::vector<size_t>& C, const Eigen::VectorXd& r0, Eigen::VectorXd& du)
{
	// The set C closed in the tangent, each with its closed side's normal force FnHat0 in place of
	// its force in YADE (the same force for one closed in YADE, less its shear): du_c. A tension Fn
	// adds -Fn b to the residual (b: the contact's normal row), so releasing tensions s >= 0 moves
	// by du = du_c + Z s, Z = J^-1 b, and the contacts' FnHat = -q - M s with q = -(FnHat0 +
	// kn'' b.du_c), M = -kn'' b^T Z. Returns false where the model is not one of a positive
	// definite J (a diagonal of I - M outside (0, 1]: measured with a factor kept at a thousandfold
	// stiffness contrast) or the pivoting does not end.
	ImplicitLinearSystem& S  = *sys;
	Eigen::VectorXd       rc = r0;
	for (size_t c : C) {
		const Interaction* I  = S.contacts[c];
		const auto*        sp = static_cast<const SwellPhys*>(I->phys.get());
		const auto&        g  = *static_cast<const ScGeom*>(I->geom.get());
		const Vector3r     f  = -sp->normalForce - sp->shearForce; // on body 1, as the law applies it
		const Vector3r     torque = g.normal.cross(f);
		const Real         l1 = g.radius1 - 0.5 * g.penetrationDepth, l2 = g.radius2 - 0.5 * g.penetrationDepth;
		Real               val[12];
		if (S.nb == 3) {
			const Real v2[6] = { f[0], f[1], l1 * torque[2], -f[0], -f[1], l2 * torque[2] };
			std::copy(v2, v2 + 6, val);
		} else
			for (int d = 0; d < 3; ++d)
				val[d] = f[d], val[3 + d] = l1 * torque[d], val[6 + d] = -f[d], val[9 + d] = l2 * torque[d];
		int eq[LowRankColumn::kSize];
		S.equationsOf(I, eq);
		for (int k = 0; k < S.nc(); ++k)
			if (eq[k] >= 0) rc[eq[k]] -= val[k];
		addNormalRow(I, -sp->state.trial.FnHat, rc);
	}
	const Eigen::VectorXd duC = solveWithCoupling(rc);
	const long            m   = long(C.size());
	Eigen::MatrixXd       Z(S.nEq, m);
	for (long j = 0; j < m; ++j) {
		Eigen::VectorXd b = Eigen::VectorXd::Zero(S.nEq);
		addNormalRow(S.contacts[C[j]], 1.0, b);
		Z.col(j) = solveWithCoupling(b);
	}
	Eigen::MatrixXd A = Eigen::MatrixXd::Identity(m, m);
	Eigen::VectorXd q(m);
	for (long i = 0; i < m; ++i) {
		const Interaction* I  = S.contacts[C[i]];
		const auto*        sp = static_cast<const SwellPhys*>(I->phys.get());
		q[i]                  = -(sp->state.trial.FnHat + sp->state.kn * kinkOpening(I, duC));
		for (long j = 0; j < m; ++j)
			A(i, j) -= sp->state.kn * kinkOpening(I, Z.col(j));
		if (!(A(i, i) > 0 && A(i, i) <= 1 + 1e-9)) return false;
	}
	Eigen::VectorXd s;
	if (!solveLcp(A, q, s, 10 * int(m) + 100)) return false;
	du = duC + Z * s;
	return du.allFinite();
}

long ImplicitLogTimeSolver::settleKinks(Eigen::VectorXd& du, const Eigen::VectorXd& r0)
{
	// A broken contact is piecewise linear: FnHat = FnHat0 + kn'' (opening increment), and it
	// carries Fn = min(FnHat, 0), with its shear, only while closed. Newton's tangent has the slope
	// of the side the contact is on, so a move that takes it across the kink is predicted with the
	// wrong one. A just-broken contact of a stiff aggregate (kn'' a thousand times the matrix's)
	// opens by about 1e-10 m: the tangent without it moves it across by far more, the contact then
	// pushes back with a thousand times the residual, and the next move opens it again (measured:
	// the ratio from 0.26 to 3.5 in one move, which the line search could not bring down, contacts
	// flipping at every iteration until relaxation took the step). Taking each such contact on the
	// side it lands on does not settle it either (measured: a few of them on their kinks flip back
	// and forth together, period 4). So the move is solved exactly for the piecewise linear model of
	// the contacts it takes across their kink (kinkModel): the LCP (I - M) s + q >= 0, s >= 0,
	// complementary, whose I - M is diagonally similar to I - K^1/2 b^T J^-1 b K^1/2, positive
	// definite since J holds these contacts' stiffness and more: a P-matrix, for which the
	// pivoting ends. Contacts that the new move takes across their kink join the set, at most
	// kinkPasses times. Returns the size of the set.
	// It runs only in a round in which the line search has rejected a whole move (kinkRound), the
	// mark of that overshoot: on every move that crossed a kink it also changed the path of runs
	// that Newton's own moves settle (12 mm, strengths x 1e-9, 10 steps a decade: 78 % of the
	// mortar contacts broken against 100 %; aggregates x 1e6, seeds 1 and 3, stopped at step 6).
	ImplicitLinearSystem& S = *sys;
	std::vector<size_t>   C;
	for (long round = 0; round < kinkPasses; ++round) {
		const size_t before = C.size();
		for (size_t c = 0; c < S.contacts.size(); ++c) {
			const Interaction* I  = S.contacts[c];
			const auto*        sp = dynamic_cast<const SwellPhys*>(I->phys.get());
			if (S.kink[c] || !sp || !sp->state.trial.broken) continue;
			const bool closedNow = sp->state.trial.FnHat < 0;
			const bool lands     = sp->state.trial.FnHat + sp->state.kn * kinkOpening(I, du) < 0;
			if (lands != closedNow) C.push_back(c), S.kink[c] = 1;
		}
		if (C.size() == before) break;
		++kinkSolves;
		assembleTangent(false, false);
		if (needsFactor(false)) {
			if (S.changed > 0) assembleTangent(false, true);
			factor();
		}
		Eigen::VectorXd next;
		bool            solved = kinkModel(C, r0, next);
		if (!solved) {
			// A kept factor is within refactorTolerance of the largest entry, a stiff aggregate's:
			// the matrix's entries may then be off by their own size, and the model with them.
			assembleTangent(false, true);
			factor();
			solved = kinkModel(C, r0, next);
		}
		if (!solved) break; // the last move stands
		du = next;
	}
	return long(C.size());
}

void ImplicitLogTimeSolver::newtonStep()
{
	if (!sys) sys = std::make_unique<ImplicitLinearSystem>();
	ImplicitLinearSystem& S      = *sys;
	const auto&           bodies = scene->bodies->body;
	const auto&           L      = scene->interactions->linIntrs;
	const int             nb     = dofsPerBody();
	lineMove.assign(nb * bodies.size(), 0.0);
	S.contacts.clear();
	S.contacts.reserve(scene->interactions->currSize);
	for (size_t i = 0; i < scene->interactions->currSize; ++i)
		if (L[i]->isReal()) S.contacts.push_back(L[i].get());
	numberEquations();
	if (S.nEq == 0) return;

	// The residual, from YADE's forces.
	Eigen::VectorXd r(S.nEq);
	for (const auto& b : bodies) {
		if (!b) continue;
		const Vector3r& f = scene->forces.getForce(b->id);
		const Vector3r& t = scene->forces.getTorque(b->id);
		const Real      val2[3] = { f[0], f[1], t[2] }, val3[6] = { f[0], f[1], f[2], t[0], t[1], t[2] };
		const Real*     val     = nb == 3 ? val2 : val3;
		for (int d = 0; d < nb; ++d)
			if (S.dofOf[nb * b->id + d] >= 0) r[S.dofOf[nb * b->id + d]] = val[d];
	}
	S.mech.assign(bodies.size(), 0);
	for (int id : heldMechanisms)
		if (id >= 0 && size_t(id) < S.mech.size()) S.mech[id] = 1;
	S.kink.assign(S.contacts.size(), 0);
	// Tangent, factor, solve; again (at most 4 times) when the move shows new mechanisms.
	Eigen::VectorXd du;
	for (int pass = 0;; ++pass) {
		const bool fresh = iterInStep == 1 && pass == 0;
		assembleTangent(pass == 0, fresh);
		if (needsFactor(fresh)) {
			if (S.changed > 0) assembleTangent(false, true);
			factor();
		}
		du = solveWithCoupling(r);
		if (!du.allFinite()) fail("the linear solve gave a non-finite displacement");
		if (holdMechanisms(du) == 0 || pass >= 4) break;
	}
	if (kinkPasses > 0 && kinkRound) settleKinks(du, r);
	// Move the bodies through their velocities.
	for (const auto& b : bodies) {
		if (!b) continue;
		const int* e    = &S.dofOf[nb * b->id];
		auto       move = [&](int d) { return e[d] >= 0 ? du[e[d]] : 0.0; };
		Real*      m    = &lineMove[nb * b->id];
		// A mechanism's direction has next to no stiffness (the regularization), so its Newton move
		// is unbounded: it goes at most maxMove radii per iteration, as if it slid or rolled.
		const Real cap = maxMove * bodyRadius[b->id];
		if (nb == 3) {
			Vector2r u(move(0), move(1));
			Real     th = move(2);
			if (bodyRadius[b->id] > 0) {
				if (u.norm() > cap) u *= cap / u.norm();
				if (std::abs(th) > maxMove) th = th > 0 ? maxMove : -maxMove;
			}
			m[0] = u[0], m[1] = u[1], m[2] = th;
			continue;
		}
		Vector3r u(move(0), move(1), move(2)), th(move(3), move(4), move(5));
		if (bodyRadius[b->id] > 0) {
			if (u.norm() > cap) u *= cap / u.norm();
			if (th.norm() > maxMove) th *= maxMove / th.norm();
		}
		for (int d = 0; d < 3; ++d)
			m[d] = u[d], m[3 + d] = th[d];
	}
	moveBodies(1.0);
}

Real ImplicitLogTimeSolver::residualMerit()
{
	// From the scene and saved attributes alone (not from the linear system, which a loaded scene
	// rebuilds later), so that a reload continues exactly. The discs' radii come from their
	// contacts' geometry (the shape is not declared here); newtonStep, which runs after it in the
	// same iteration, caps its moves with them.
	const auto& bodies = scene->bodies->body;
	std::vector<Real>& radius = bodyRadius;
	radius.assign(bodies.size(), 0.0);
	const auto& L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i) {
		const Interaction* I = L[i].get();
		if (!I->isReal()) continue;
		const auto* g  = static_cast<const ScGeom*>(I->geom.get());
		radius[I->id1] = std::max(radius[I->id1], g->radius1);
		radius[I->id2] = std::max(radius[I->id2], g->radius2);
	}
	const unsigned* axisBit = dofBits();
	const int       nb      = dofsPerBody();
	Real            s       = 0;
	for (const auto& b : bodies) {
		if (!b || b->isClump()) continue;
		const Vector3r& f = scene->forces.getForce(b->id);
		const Vector3r& t = scene->forces.getTorque(b->id);
		const Real      r = radius[b->id] > 0 ? radius[b->id] : 1.0;
		const Real      val2[3] = { f[0], f[1], t[2] / r }, val3[6] = { f[0], f[1], f[2], t[0] / r, t[1] / r, t[2] / r };
		const Real*     val     = nb == 3 ? val2 : val3;
		for (int d = 0; d < nb; ++d)
			if (!(b->state->blockedDOFs & axisBit[d]) && std::find(pinnedDofs.begin(), pinnedDofs.end(), nb * b->id + d) == pinnedDofs.end())
				s += val[d] * val[d];
	}
	return std::sqrt(s);
}

void ImplicitLogTimeSolver::moveBodies(Real fraction)
{
	// Through the velocities too: YADE's ScGeom takes the shear increment from them.
	const Real dt = scene->dt;
	const int  nb = dofsPerBody(), nd = nb == 6 ? 3 : 2;
	for (const auto& b : scene->bodies->body) {
		if (!b || nb * size_t(b->id) + nb - 1 >= lineMove.size()) continue;
		State*      s = b->state.get();
		const Real* m = &lineMove[nb * b->id];
		for (int d = 0; d < nd; ++d) {
			s->vel[d] = fraction * m[d] / dt;
			s->se3.position[d] += fraction * m[d];
		}
		if (nb == 3) {
			const Real th = fraction * m[2];
			s->angVel     = Vector3r(0, 0, th / dt);
			if (th != 0) {
				s->se3.orientation = Quaternionr(Eigen::AngleAxis<Real>(th, Vector3r::UnitZ())) * s->se3.orientation;
				s->se3.orientation.normalize();
			}
			continue;
		}
		const Vector3r th = fraction * Vector3r(m[3], m[4], m[5]);
		s->angVel         = th / dt;
		if (th.norm() > 0) {
			s->se3.orientation = Quaternionr(Eigen::AngleAxis<Real>(th.norm(), th.normalized())) * s->se3.orientation;
			s->se3.orientation.normalize();
		}
	}
}

void ImplicitLogTimeSolver::relaxIteration(const Balance& b)
{
	// New contacts change the Gershgorin bound; a break only lowers a stiffness, which keeps it safe.
	if (b.nReal != relax.nContactsSeen) {
		relax.computeMasses(scene, DynamicRelaxation::kDefaultMassSafety);
		forEachSpring([this](int id, int axis, Real k) { relax.addStiffness(scene, DynamicRelaxation::kDefaultMassSafety, id, axis, k); });
	}
	relax.leapfrog(scene, relax.damping(scene, DynamicRelaxation::kDefaultMaxDamping));
	++relaxationIterations;
}

void ImplicitLogTimeSolver::syncShearMode()
{
	// A step handed to dynamic relaxation takes the shear as the ADR does, YADE's incremental vector
	// (the contacts' current shear force, ScGeom's increments), whose slip is permanent at every
	// iteration: relaxation among sliding contacts needs that dissipation. With the shear from the
	// step's start a slip is undone when the contact moves back, and the relaxation crawls (measured
	// on a stiff-aggregate step: no equilibrium in 555,000 iterations where the ADR needed 133,000).
	const bool fromStart = shearFromStepStart && !fallback;
	if (law2->shearFromStepStart != fromStart) law2->setLogTimeModes(fromStart);
}

void ImplicitLogTimeSolver::action()
{
	if (!startIteration()) return;
	if (iterInStep == 1) relaxationAtStepStart = relaxationIterations, factorizationsAtStepStart = factorizations, krylovAtStepStart = krylovIterations;
	const Balance b = measureBalance();
	const TrackHeldBodiesAtExit track { this };
	// A round whose Newton iterations have not reached `tolerance` after newtonLimit (a broken contact
	// sitting on its open / closed kink keeps the residual from falling further) is settled once it
	// is within stallTolerance, and counted.
	if (iterInStep == 1) fallback = false;
	// A round that Newton and its relaxation phases have not settled within fallbackIterations (an
	// active set that keeps changing: measured on 12 mm specimens with every strength near zero, 40
	// to 60 contacts flipping each iteration) goes on by dynamic relaxation alone for the rest of the
	// step, to the ADR's accuracy, as the ADR takes every step.
	if (!fallback && fallbackIterations > 0 && iterInStep - roundStart > fallbackIterations) {
		fallback           = true;
		fallbackRelaxStart = relaxationIterations;
		fallbackRatio.push_back(b.ratio);
		fallbackChanging.push_back(int(activeChanges));
		if (verbose) {
			std::printf("swelldem: step %d/%d: Newton has not settled after %ld iterations; the step goes on by dynamic relaxation to %s\n", step,
			            nSteps(), fallbackIterations, fallbackDetail().c_str());
			std::fflush(stdout);
		}
		relaxing = false; // restarted from rest below
	}
	syncShearMode();
	// The first iteration of a round measures its load before any Newton move (a step's offsets, or
	// the forces the breaks released). Its ratio counts each contact at least with the load its
	// offset imposes, so it starts at or below about 1: a loose tolerance would commit the unmoved
	// state (measured: zero strain at 0.9). The tolerance is therefore met only after a move; a
	// residual at the positions' round-off is met at once (a step that loads nothing).
	const bool        moved   = iterInStep - roundStart >= 2;
	const bool        exact   = (moved && b.ratio <= tolerance) || b.atRoundOff;
	const bool        stalled = !exact && !fallback && (iterInStep - newtonSince > newtonLimit || changingHandOver) && b.ratio <= stallTolerance;
	const bool        relaxed = fallback && b.ratio <= std::max(tolerance, fallbackTolerance);
	const StepOutcome out     = settleStep(b, exact || stalled || relaxed);
	if (stalled && out != StepOutcome::Continue) ++stalledRounds;
	if (out != StepOutcome::Continue || iterInStep == 1)
		relaxing = false, newtonSince = iterInStep, relaxPhase = 0, lineAlpha = 0, heldMechanisms.clear(),
		kinkRound = false, changingHandOver = false;
	if (out == StepOutcome::Committed) {
		fallback = false;
		syncShearMode(); // before the next step's first pass
		return;
	}
	if (out == StepOutcome::Broke) { // the next pass computes the forces without the broken contacts
		zeroVelocities(scene);
		return;
	}
	if (fallback) {
		if (!relaxing) {
			relaxing  = true;
			lineAlpha = 0;
			zeroVelocities(scene);
			relax.start(scene, nDim);
		}
		relaxIteration(b);
		return;
	}
	// After a 3D cracking round's breaks 30 to 100 contacts change state at every Newton iteration,
	// and each such iteration refactors and solves the sliding contacts' columns anew (20 mm cube:
	// about 5 s, some 60 relaxation iterations); once contacts have broken, the broken ones' kinks
	// and slips leave Newton's later iterations linear at best. A Newton phase of a specimen with
	// broken contacts, or one still changing contacts' states, hands the round to relaxation after
	// changingLimit iterations, which settles it within stallTolerance. An intact specimen keeps
	// newtonLimit, and Newton's exact equilibrium.
	const long cLimit   = changingLimitOfDimension();
	const bool changing = cLimit > 0 && (activeChanges > 0 || law2->nBreaks > 0) && iterInStep - newtonSince > cLimit;
	if (!relaxing && (iterInStep - newtonSince > newtonLimit || changing)) {
		changingHandOver = changingHandOver || changing;
		relaxing  = true;
		lineAlpha = 0;
		zeroVelocities(scene);
		relax.start(scene, nDim);
		++relaxPhase;
	}
	if (relaxing) {
		if (b.ratio > relaxTolerance * std::pow(1e-2, relaxPhase - 1)) {
			relaxIteration(b);
			return;
		}
		relaxing    = false;
		newtonSince = iterInStep;
	}
	// Backtracking on the residual's 2-norm, for which a Newton move is a descent direction (the
	// unbalanced ratio, a mean of per-body force norms, is not: measured, it stalls the search on
	// 40 mm elastic runs that the 2-norm settles). A full move can jump across a broken contact's
	// kink (open / closed) and back again; part of it lands on the side it stays on.
	const Real merit = residualMerit();
	if (lineAlpha > 0) {
		if (merit > (1 - 1e-4 * lineAlpha) * lineRatio0 && lineAlpha > 1.0 / 64) {
			moveBodies(-0.5 * lineAlpha);
			lineAlpha *= 0.5;
			++backtracks;
			return;
		}
		// No part of the move lowered the residual: the mark of a move across a stiff broken
		// contact's kink (settleKinks); the round's moves are solved as that LCP from now on.
		if (merit > (1 - 1e-4 * lineAlpha) * lineRatio0) kinkRound = true;
	}
	// Inexact Newton (petsc-gamg): a move is solved to the relative residual that would bring a
	// linear step to the tolerance (0.1 tolerance / ratio, at least 1e-8, at most 0.1), and while
	// contacts change state, when the next residual depends more on the active set than on the move's
	// accuracy, no further than Eisenstat and Walker's choice 2 (gamma 0.9, alpha 2) asks.
	forcing = std::clamp(0.1 * tolerance / std::max(b.ratio, Real(1e-300)), Real(1e-8), Real(0.1));
	if (activeChanges > 0 && lineRatio0 > 0 && lineAlpha > 0)
		forcing = std::max(forcing, std::min(Real(0.1), Real(0.9) * (merit / lineRatio0) * (merit / lineRatio0)));
	newtonStep();
	lineAlpha  = 1;
	lineRatio0 = merit;
}

template <class F> void ImplicitLogTimeSolver::petscOrFail(F&& call)
{
	// PETSc's errors arrive as exceptions of the module; each becomes the run's stop message
	try {
		call();
	} catch (const std::exception& e) {
		fail(std::string("linear solver ") + linearSolverUsed + ": " + e.what());
	}
}

void ImplicitLogTimeSolver::openLinearSolver()
{
	// The solver for the pattern just made, and the rigid-body modes GAMG's coarse levels must keep:
	// every body translating (2D: x, y; 3D: x, y, z) and turning about the specimen's centre (2D: z;
	// 3D: x, y, z), over the free equations; a turn moves a body by w x (p - c) and turns it by w.
	ImplicitLinearSystem& S = *sys;
	petscOrFail([&] {
		if (!S.petsc || linearSolverUsed != S.petsc->name()) S.petsc = swelldem::linalg::openPetsc(linearSolverUsed);
		// a body's DOFs are a block (multigrid aggregates bodies); bodies with none free are left out
		std::vector<int> fullOf(size_t(S.nEq), -1);
		int              blocks = 0;
		for (size_t id = 0; id * S.nb < S.dofOf.size(); ++id) {
			bool any = false;
			for (int d = 0; d < S.nb; ++d)
				if (S.dofOf[S.nb * id + d] >= 0) fullOf[size_t(S.dofOf[S.nb * id + d])] = S.nb * blocks + d, any = true;
			blocks += any;
		}
		S.petsc->setBlocks(S.nEq, S.nb, S.nb * blocks, fullOf.data());
		S.petsc->setMatrix(S.nEq, S.K.outerIndexPtr(), S.K.innerIndexPtr(), S.K.valuePtr());
		if (!S.petsc->iterative()) return;
		const auto& bodies = scene->bodies->body;
		const int   nb     = S.nb, nModes = nb == 6 ? 6 : 3, nt = nb == 6 ? 3 : 2;
		Vector3r    c      = Vector3r::Zero();
		long        n      = 0;
		for (const auto& b : bodies)
			if (b && !b->isClump()) c += b->state->se3.position, ++n;
		if (n > 0) c /= Real(n);
		std::vector<double> modes(size_t(nModes) * S.nEq, 0.0);
		auto                set = [&](int mode, int id, int axis, double value) {
                        const int e = S.dofOf[nb * id + axis];
                        if (e >= 0) modes[size_t(mode) * S.nEq + e] = value;
		};
		for (const auto& b : bodies) {
			if (!b || b->isClump()) continue;
			const Vector3r p = b->state->se3.position - c;
			for (int d = 0; d < nt; ++d)
				set(d, b->id, d, 1.0);
			if (nb == 3) {
				set(2, b->id, 0, -p[1]), set(2, b->id, 1, p[0]), set(2, b->id, 2, 1.0);
				continue;
			}
			for (int k = 0; k < 3; ++k) {
				Vector3r w = Vector3r::Zero();
				w[k]                = 1;
				const Vector3r move = w.cross(p);
				for (int d = 0; d < 3; ++d)
					set(3 + k, b->id, d, move[d]);
				set(3 + k, b->id, 3 + k, 1.0);
			}
		}
		S.petsc->setNearNullSpace(nModes, modes.data());
	});
}

bool ImplicitLogTimeSolver::factorValues()
{
	ImplicitLinearSystem& S = *sys;
	if (!S.petsc) {
		const SerialOpenMP serial;
		S.chol.factorize(S.K);
		return S.chol.info() == Eigen::Success;
	}
	petscOrFail([&] {
		S.petsc->setMatrix(S.nEq, S.K.outerIndexPtr(), S.K.innerIndexPtr(), S.K.valuePtr());
		S.petsc->setup();
	});
	return true;
}

Eigen::MatrixXd ImplicitLogTimeSolver::directSolve(const Eigen::MatrixXd& b)
{
	ImplicitLinearSystem& S = *sys;
	if (!S.petsc) return S.chol.solve(b);
	Eigen::MatrixXd x(b.rows(), b.cols());
	petscOrFail([&] {
		for (long j = 0; j < b.cols(); ++j) {
			const Eigen::VectorXd col = b.col(j);
			Eigen::VectorXd       out(b.rows());
			S.petsc->solve(col.data(), out.data(), 0.0, {}, true, 1);
			x.col(j) = out;
		}
	});
	return x;
}

Eigen::VectorXd ImplicitLogTimeSolver::krylovSolve(const Eigen::VectorXd& r, const std::vector<const LowRankColumn*>& use)
{
	// The operator is the current tangent: K's values (with the 3D sliding contacts' stiffness across
	// their slip, as a factor would have it) and every change since the preconditioner's set-up as
	// its column; the preconditioner is GAMG's hierarchy of the last set-up, renewed where CHOLMOD
	// would refactor. No column needs a solve of its own, as Woodbury's formula does with a factor.
	ImplicitLinearSystem& S = *sys;
	std::vector<double>   values(S.K.valuePtr(), S.K.valuePtr() + S.K.nonZeros());
	if (!S.acrossInK) addAcross(S, values.data());
	std::vector<swelldem::linalg::RankOneTerm> terms(use.size());
	bool                                       symmetric = true;
	for (size_t i = 0; i < use.size(); ++i) {
		std::copy(use[i]->eq, use[i]->eq + 12, terms[i].eq);
		std::copy(use[i]->u, use[i]->u + 12, terms[i].u);
		std::copy(use[i]->v, use[i]->v + 12, terms[i].v);
		symmetric = symmetric && use[i]->type != 2;
	}
	Eigen::VectorXd du(S.nEq);
	petscOrFail([&] {
		S.petsc->setMatrix(S.nEq, S.K.outerIndexPtr(), S.K.innerIndexPtr(), values.data());
		const auto report = S.petsc->solve(r.data(), du.data(), forcing, terms, symmetric, int(gmresLimit));
		++krylovSolves, krylovIterations += report.iterations;
		if (!report.converged) {
			++krylovFailures;
			// a solve at gmresLimit is the rule, not news; a breakdown is
			if (verbose && !report.atLimit) {
				std::printf("swelldem: step %d/%d: the Krylov solve stopped at relative residual %.2e (asked %.1e) after %d iterations: %s\n",
				            step, nSteps(), report.residual, double(forcing), report.iterations, report.reason.c_str());
				std::fflush(stdout);
			}
		}
	});
	return du;
}

} // namespace yade
