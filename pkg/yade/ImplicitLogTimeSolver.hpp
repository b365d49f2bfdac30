// SPDX-License-Identifier: GPL-2.0-or-later
// Exact quasi-static solver: within a physical step every intact contact is linear (kn'', ks'' and
// the imposed creep + swelling displacements are fixed), so the step's equilibrium is a sparse
// symmetric positive definite system K du = r. Each iteration takes r from YADE itself (the
// bodies' forces after the InteractionLoop pass of the real contact law: the law stays the only
// force path), solves with a CHOLMOD supernodal Cholesky factor of the tangent stiffness and moves
// the bodies by du through their velocities (ScGeom integrates the shear from them). A linear
// step converges in one solve plus the pass that checks it; damage and the broken contacts'
// open / sticking / sliding states make it an active-set Newton iteration (core::ContactLaw::mode),
// a move across broken contacts' open / closed kink being solved as those contacts' complementarity
// problem (kinkPasses), and where that active set does not settle within newtonLimit iterations (a
// disc rolling between sliding contacts, contacts changing state at every iteration) dynamic
// relaxation takes the step down to relaxTolerance and Newton finishes it. The factor is reused
// while the tangent is unchanged and its symbolic analysis while the contact graph is.
#pragma once
#include "DynamicRelaxation.hpp"
#include <memory>

namespace yade {

struct ImplicitLinearSystem; // the sparse matrix and its factor (Eigen + CHOLMOD), kept out of this header

// A column pair (u, v) of the tangent J = K_factored + sum u v^T: a contact whose stiffness changed
// since the factor was made (type 0 normal, 1 shear, 4 a 3D contact's second shear: u = dk b,
// v = b), a sliding contact's shear-normal coupling (type 2: u = slide bs, v = bn, bs along its
// shear force) or a diagonal entry brought to the exact one (type 3: id1 = -1 - equation). The
// columns whose K^-1 u is kept with the factor are saved with the scene, so that a reloaded one
// solves the same columns in the same order.
struct LowRankColumn {
	static constexpr int kSize = 12; // a 3D contact's DOFs; a 2D one uses the first 6
	int  id1, id2, type;
	Real value; // the change dk or the slope [N/m]
	int  eq[kSize]; // equations of the contact's DOFs (body 1's, then body 2's), -1 where held or unused
	Real u[kSize], v[kSize];
	template <class Archive> void serialize(Archive& ar, unsigned)
	{
		ar& boost::serialization::make_nvp("id1", id1);
		ar& boost::serialization::make_nvp("id2", id2);
		ar& boost::serialization::make_nvp("type", type);
		ar& boost::serialization::make_nvp("value", value);
		ar& boost::serialization::make_nvp("eq", eq);
		ar& boost::serialization::make_nvp("u", u);
		ar& boost::serialization::make_nvp("v", v);
	}
};

} // namespace yade
BOOST_CLASS_IMPLEMENTATION(yade::LowRankColumn, boost::serialization::object_serializable)
BOOST_CLASS_TRACKING(yade::LowRankColumn, boost::serialization::track_never)

namespace yade {

class ImplicitLogTimeSolver : public LogTimeSolver {
public:
#define SWELLDEM_IMPLICIT_ATTRS(X)                                                                                                                             \
	X(string, linearSolver, "auto", swelldem_attr::Setting,                                                                                              \
	  "Solver of each Newton move's sparse system: auto (the default: cholmod, unless its factor of a 3D system would pass "                \
	  "autoFactorMemoryShare of the memory or the run has more than one MPI rank, then petsc-gamg where PETSc can be loaded; decided on "    \
	  "the run's first system, see linearSolverUsed), cholmod (CHOLMOD's supernodal Cholesky factor), petsc-gamg (PETSc's conjugate "            \
	  "gradients preconditioned by its algebraic multigrid GAMG, which is given the bodies' rigid-body modes and aggregates bodies; GMRES "    \
	  "while sliding contacts' coupling makes the tangent unsymmetric; each solve only as exact as the Newton iteration needs), petsc-mumps " \
	  "(MUMPS's Cholesky factor through PETSc). PETSc's own options reach its solvers with the prefix swelldem_ (PETSC_OPTIONS) [-]")         \
	X(Real, autoFactorMemoryShare, 0.6, swelldem_attr::Setting,                                                                                       \
	  "With linearSolver auto, the share of the machine's physical memory above which the peak of CHOLMOD's factorization of a 3D "        \
	  "system (11.5 bytes an entry of the factor, known from its analysis before any factorization) sends the run to petsc-gamg [-]")    \
	X(long, gmresLimit, 100, swelldem_attr::Setting,                                                                                                   \
	  "petsc-gamg: iterations after which a GMRES solve (the tangent made unsymmetric by sliding contacts' shear-normal coupling) stops; "  \
	  "its move, the least residual over those iterations, goes through the line search as a converged one does [-]")                        \
	X(string, linearSolverUsed, "", swelldem_attr::Result, "The linear solver the run uses (linearSolver, auto resolved); empty before its first system [-]") \
	X(long, krylovSolves, 0, swelldem_attr::Result, "Linear solves by a Krylov method (petsc-gamg) so far [-]")                                   \
	X(long, krylovIterations, 0, swelldem_attr::Result, "Krylov iterations of those solves so far [-]")                                            \
	X(long, krylovFailures, 0, swelldem_attr::Result,                                                                                                  \
	  "Krylov solves that stopped before their tolerance, at gmresLimit or by a breakdown (their move still goes through the line search) so far [-]")                          \
	X(Real, regularization, 1e-12, swelldem_attr::Setting,                                                                                                \
	  "Relative diagonal shift of the tangent for local mechanisms (a disc held by one contact, open cracks): it changes "                         \
	  "the iteration path, never the converged equilibrium, which is YADE's residual at the tolerance [-]")                                         \
	X(Real, rotationRegularization, -1, swelldem_attr::Setting,                                                                                         \
	  "Diagonal shift of the tangent's rotations, relative to each particle's own diagonal and at most to the median particle's: a disc held "  \
	  "by one contact can roll about it (no stiffness in the tangent), and the shift bounds its move along that mode; rotations converge by "  \
	  "this factor an iteration, the equilibrium is YADE's residual; < 0: by dimension, 1e-3 for discs (cracking sections settle faster), "  \
	  "1e-5 for spheres with a factor (a 12 mm ISR cube: 542 Newton iterations against 883 at 1e-3) and 1e-3 for spheres with petsc-gamg "  \
	  "(whose CG stagnates on nearly free rotations at 1e-5: the 40 mm ISR cube) [-]")                                              \
	X(Real, refactorTolerance, 1e-3, swelldem_attr::Setting,                                                                                            \
	  "The Cholesky factor is kept while no entry of the tangent differs from the factored one by more than this fraction of the largest "    \
	  "entry (the geometry moving within a step; a state change, a break or an aging kind's new step differ by far more); the iteration is "   \
	  "then a modified Newton step on YADE's exact residual; 0: refactor at any change [-]")                                                   \
	X(Real, maxMove, 0.05, swelldem_attr::Setting,                                                                                                       \
	  "Largest move of a disc in one iteration, as a fraction of its radius: a disc that nothing holds in some direction (a mechanism: "         \
	  "sliding or open contacts only) moves at most this far per iteration, until it meets a neighbour or an equilibrium [-]")                    \
	X(Real, mechanismMove, 1e-2, swelldem_attr::Setting,                                                                                                \
	  "Relative move across a contact, as a fraction of the mean radius, above which a Newton move is taken as a mechanism's (a disc that its "  \
	  "sliding contacts do not hold in some direction): the sliding contacts of both discs then enter the tangent as sticking for the rest of " \
	  "the round, so that the disc slides by elastic amounts per iteration instead of jumping (the elastic predictor's tangent); 0: never [-]")                                             \
	X(long, newtonLimit, 20, swelldem_attr::Setting,                                                                                                    \
	  "Newton iterations without reaching the tolerance after which the step continues by dynamic relaxation (a broken contact's "               \
	  "open / closed / sliding state that does not settle under Newton) [-]")                                                                       \
	X(long, changingLimit, -1, swelldem_attr::Setting,                                                                                                  \
	  "Newton iterations after which a round of a specimen with broken contacts, or whose last iteration still changed the state of "       \
	  "contacts, goes on by dynamic relaxation, as after newtonLimit, and is settled as soon as it is within stallTolerance: after a 3D "     \
	  "cracking round's breaks 30 to 100 contacts change state at every iteration, each of which then refactors (20 mm ISR cube: about "     \
	  "5 s an iteration); -1: by dimension, none for discs and 2 for spheres; 0: none [-]")                                                      \
	X(Real, relaxTolerance, 1e-4, swelldem_attr::Setting,                                                                                                \
	  "Unbalanced-force ratio at which dynamic relaxation hands back to Newton; each further relaxation of the same round goes 100x lower [-]")  \
	X(Real, stallTolerance, 1e-5, swelldem_attr::Setting,                                                                                                \
	  "Unbalanced-force ratio at which a round that Newton has not brought to `tolerance` within newtonLimit iterations is settled "            \
	  "(a broken contact on its open / closed kink; 10x below the ADR's default tolerance), or that changingLimit has handed to "               \
	  "relaxation; 0: never [-]")                                                                                                                  \
	X(long, lowRankChanges, 16, swelldem_attr::Setting,                                                                                              \
	  "Contacts changing state (open, closed, sticking, sliding) since the factor was made, up to which the changes enter the solve "        \
	  "exactly as low-rank columns (one solve each, Woodbury) instead of a new factorization; 0: refactor at any change [-]")                     \
	X(long, fallbackIterations, 5000, swelldem_attr::Setting,                                                                                          \
	  "Iterations of a round (a step, or its part between breaks) after which, if neither tolerance nor stallTolerance is reached, the rest " \
	  "of the step goes by dynamic relaxation alone to fallbackTolerance, as the ADR would take it (recorded in fallbackSteps); 0: never [-]")   \
	X(Real, fallbackTolerance, 1e-4, swelldem_attr::Setting,                                                                                           \
	  "Unbalanced-force ratio at which a step handed to dynamic relaxation (fallbackIterations) is in equilibrium: the ADR's default "          \
	  "tolerance, so that such a step has the ADR's accuracy [-]")                                                                                   \
	X(long, kinkPasses, 8, swelldem_attr::Setting,                                                                                                  \
	  "In a round in which the line search has rejected a whole Newton move (kinkRound), a move that takes broken contacts across their "    \
	  "open / closed kink is solved again as the complementarity problem (LCP) of those contacts' piecewise linear forces; contacts the new " \
	  "move takes across theirs join it, at most this many times; 0: never [-]")                                                              \
	X(long, kinkSolves, 0, swelldem_attr::Result, "Newton moves solved as the LCP of the broken contacts they take across their kink (kinkPasses) so far [-]") \
	X(long, maxSlidingExact, 1000, swelldem_attr::Setting,                                                                                              \
	  "Sliding contacts up to which their shear-normal coupling enters the Newton solve exactly (one extra solve each); above, it is left out [-]") \
	X(long, stalledRounds, 0, swelldem_attr::Result, "Rounds (a step, or its part between breaks) settled at stallTolerance, not at tolerance [-]") \
	X(long, backtracks, 0, swelldem_attr::Result, "Newton moves halved by the line search so far [-]")                                             \
	X(long, relaxationIterations, 0, swelldem_attr::Result, "Iterations done by dynamic relaxation so far [-]")                                      \
	X(long, mechanismHolds, 0, swelldem_attr::Result, "Discs whose sliding contacts were taken as sticking (mechanismMove) so far, once a round [-]") \
	X(long, factorizations, 0, swelldem_attr::Result, "Numeric Cholesky factorizations so far [-]")                                                    \
	X(long, analyses, 0, swelldem_attr::Result, "Symbolic analyses (contact graph changes) so far [-]")                                               \
	X(Real, factorSeconds, 0.0, swelldem_attr::Result, "Wall time spent in numeric Cholesky factorizations so far [s]")         \
	X(Real, factorNonZeros, 0.0, swelldem_attr::Result,                                                                                              \
	  "Entries of the Cholesky factor L of the last symbolic analysis (its fill-in; K's lower triangle has about 21 per 2D contact, 78 per 3D one) [-]") \
	X(std::vector<int>, fallbackSteps, std::vector<int>(), swelldem_attr::Result,                                                                     \
	  "Physical steps (1..nSteps) that Newton did not settle within fallbackIterations and dynamic relaxation finished [-]")                      \
	X(std::vector<Real>, fallbackRatio, std::vector<Real>(), swelldem_attr::Result,                                                                  \
	  "Unbalanced-force ratio at which each step of fallbackSteps was handed to dynamic relaxation [-]")                                          \
	X(std::vector<int>, fallbackChanging, std::vector<int>(), swelldem_attr::Result,                                                                 \
	  "Contacts changing state (open, closed, sticking, sliding) in the last Newton iteration before each hand-over of fallbackSteps [-]")         \
	X(std::vector<int>, fallbackRelaxation, std::vector<int>(), swelldem_attr::Result,                                                               \
	  "Dynamic relaxation iterations from the hand-over to the end of each step of fallbackSteps [-]")                                          \
	X(std::vector<Real>, fallbackWall, std::vector<Real>(), swelldem_attr::Result,                                                                   \
	  "Wall time of each step of fallbackSteps, from its start to its end [s]")                                                                     \
	X(long, activeChanges, 0, swelldem_attr::Result, "Contacts whose state (intact, open, sticking, sliding) changed in the last iteration [-]")              \
	X(std::vector<int>, pinnedDofs, std::vector<int>(), swelldem_attr::Internal,                                                                       \
	  "Degrees of freedom held to remove a free specimen's rigid-body modes, as n x body id + axis, n the DOFs a body (2D: 3, axes x, y, "    \
	  "rz; 3D: 6, axes x, y, z, rx, ry, rz) [-]")                                  \
	X(Real, lineAlpha, 0.0, swelldem_attr::Internal, "Fraction of the last Newton move being tried by the line search (0: none) [-]")               \
	X(Real, lineRatio0, 0.0, swelldem_attr::Internal, "Residual 2-norm over the free DOFs before the last Newton move (torques over the radius) [N]") \
	X(std::vector<Real>, lineMove, std::vector<Real>(), swelldem_attr::Internal,                                                                     \
	  "The last Newton move per body: 2D x, y, rotation z; 3D x, y, z and the rotation vector [m, rad]")  \
	X(std::vector<int>, heldMechanisms, std::vector<int>(), swelldem_attr::Internal,                                                                   \
	  "Discs whose sliding contacts enter the tangent as sticking in the current round (mechanismMove) [-]")                                        \
	X(std::vector<Real>, factoredValues, std::vector<Real>(), swelldem_attr::Internal,                                                                 \
	  "Entries of the tangent that the current Cholesky factor was computed from (kept so that a reloaded scene factors the same) [N/m; N, N m with rotations]")       \
	X(std::vector<Real>, factoredDrift, std::vector<Real>(), swelldem_attr::Internal,                                                                 \
	  "The tangent's entries without the 3D sliding contacts' stiffness across their slip, when the current factor was made with some "      \
	  "(empty otherwise): the reference of refactorTolerance [N/m; N, N m with rotations]")                                                     \
	X(std::vector<Real>, factoredAcross, std::vector<Real>(), swelldem_attr::Internal,                                                                \
	  "3D: each contact's stiffness across its slip (in factoredGraph's order; 0 where it was not sliding) in the tangent the current factor " \
	  "was computed from (empty: none sliding) [N/m]")                                                                                              \
	X(std::vector<Real>, factoredStiffness, std::vector<Real>(), swelldem_attr::Internal,                                                             \
	  "kn, ks of each contact (in factoredGraph's order) in the tangent the current factor was computed from [N/m]")                            \
	X(std::vector<LowRankColumn>, lowRankColumns, std::vector<LowRankColumn>(), swelldem_attr::Internal,                                           \
	  "Low-rank columns whose K^-1 u is kept with the current factor, in the order they were solved [N/m; N with rotations]")                    \
	X(std::vector<int>, factoredGraph, std::vector<int>(), swelldem_attr::Internal,                                                                    \
	  "Body ids (2 per contact) of the contacts the tangent's sparsity pattern was made for [-]")                                                 \
	X(bool, kinkRound, false, swelldem_attr::Internal, "The line search has rejected a whole Newton move in the current round: its moves cross kinks as their LCP (kinkPasses) [-]") \
	X(bool, relaxing, false, swelldem_attr::Internal, "The step is in a dynamic relaxation phase [-]")                                                  \
	X(bool, fallback, false, swelldem_attr::Internal, "The current step was handed to dynamic relaxation (fallbackIterations) [-]")                   \
	X(long, fallbackRelaxStart, 0, swelldem_attr::Internal, "relaxationIterations when the current step was handed over [-]")                     \
	X(long, newtonSince, 0, swelldem_attr::Internal, "Iteration of the step at which Newton (re)started [-]")                                         \
	X(bool, changingHandOver, false, swelldem_attr::Internal,                                                                                          \
	  "changingLimit has handed the current round to dynamic relaxation: it settles within stallTolerance [-]")                                   \
	X(int, relaxPhase, 0, swelldem_attr::Internal, "Dynamic relaxation phases in the current round [-]")                                             \
	X(DynamicRelaxation, relax, DynamicRelaxation(), swelldem_attr::Internal, "State of the dynamic relaxation phases [-]")
	SWELLDEM_CLASS(ImplicitLogTimeSolver, LogTimeSolver,
	               "Quasi-static log-time solver for swelldem scenes (2D discs or 3D spheres) with an exact equilibrium at each physical step: Newton "
	               "iterations on YADE's own residual with a sparse Cholesky factor (CHOLMOD) of the contacts' step stiffness, "
	               "breaks at equilibrium and an active set for broken contacts. Replaces NewtonIntegrator; put it last in "
	               "O.engines. Defaults differ from the ADR's: tolerance 1e-10 (met only after a Newton move of the round), minIterations 1, colliderPeriod 1.",
	               SWELLDEM_IMPLICIT_ATTRS)
	ImplicitLogTimeSolver();
	virtual ~ImplicitLogTimeSolver();
	void action() override;
	void postLoad();
	template <class C> static void pyMethods(C&) { }

private:
	long relaxationAtStepStart = 0, factorizationsAtStepStart = 0, krylovAtStepStart = 0; // for the progress line only
	int  dofsPerBody() const { return nDim == 3 ? 6 : 3; }       // 2D x, y, rz; 3D x, y, z, rx, ry, rz
	const unsigned* dofBits() const;                             // the blocked-DOF bit of each of them
	string fallbackDetail() const;                                 // the fallback's tolerance and hand-over, for the progress lines
	std::vector<Real> bodyRadius; // per body, the largest radius its real contacts give it (0: none); this iteration's
	void                                  choosePins();
	void                                  newtonStep();
	// the parts of a Newton iteration, on sys
	static double                         factorPeakBytes(double entries);    // CHOLMOD's factorization peak for a factor of these entries
	static double                         physicalMemoryBytes();              // 0 where unknown
	void                                  numberEquations();                  // equations, pattern and analysis when the graph changed
	std::vector<unsigned>                 heldDofMasks() const;               // per body, its blocked x, y, rz
	bool                                  sameEquations(const std::vector<unsigned>& masks) const; // the numbering still holds
	void                                  numberDofs(const std::vector<unsigned>& masks); // dofOf, nEq, isRotation
	void                                  makePattern();                      // K's sparsity pattern
	void                                  findSlots();                        // where each contact's entries live in K
	void                                  refactorSavedValues();              // a reloaded scene's factor
	void                                  assembleTangent(bool firstPass, bool exact); // K's values, the low-rank columns; activeChanges
	void                                  startAssembly();
	char                                  addContact(size_t c, bool lowRank); // its entries and columns; its state
	void                                  addStiffnessChange(size_t c, Real kn, Real ks, const Real* bn, const Real* bs, const Real* bs2, Real& kA, Real& sA);
	void                                  shiftDiagonal(Real kLoose);         // regularization, loose DOFs, rotations
	Real                                  rotationShift(Real diagonal) const; // of a rotation's diagonal entry
	Real                                  rotationShiftFactor() const; // rotationRegularization, or its dimension's default
	long                                  changingLimitOfDimension() const; // changingLimit, or its dimension's default
	void                                  addDiagonalColumns(const std::vector<Real>& raw, Real kLoose);
	bool                                  needsFactor(bool freshFactor) const; // K no longer within refactorTolerance and lowRankChanges of the factor
	void                                  factor();
	bool                                  factorValues(); // CHOLMOD's factor or PETSc's set-up of K's values; false: not positive definite
	void                                  openLinearSolver();  // the PETSc solver of the chosen kind, and its rigid-body modes
	template <class F> void               petscOrFail(F&& call); // call(), a PETSc error stopping the run with its message
	Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> directSolve(const Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>& b); // with the factor in hand
	Eigen::Matrix<Real, Eigen::Dynamic, 1> krylovSolve(const Eigen::Matrix<Real, Eigen::Dynamic, 1>& r, const std::vector<const LowRankColumn*>& use);
	Real                                  forcing = 0.1; // relative residual the next Krylov solve goes to (inexact Newton)
	Eigen::Matrix<Real, Eigen::Dynamic, 1> solveWithCoupling(const Eigen::Matrix<Real, Eigen::Dynamic, 1>& r); // K^-1 r, Woodbury for the coupling
	Real kinkOpening(const Interaction* I, const Eigen::Matrix<Real, Eigen::Dynamic, 1>& x) const; // opening by a move x
	void addNormalRow(const Interaction* I, Real scale, Eigen::Matrix<Real, Eigen::Dynamic, 1>& v) const; // v += scale b
	bool kinkModel(const std::vector<size_t>& C, const Eigen::Matrix<Real, Eigen::Dynamic, 1>& r0, Eigen::Matrix<Real, Eigen::Dynamic, 1>& du);
	long settleKinks(Eigen::Matrix<Real, Eigen::Dynamic, 1>& du, const Eigen::Matrix<Real, Eigen::Dynamic, 1>& r); // the move's kinks
	long                                  holdMechanisms(const Eigen::Matrix<Real, Eigen::Dynamic, 1>& du); // discs newly held (mechanismMove)
	void                                  relaxIteration(const Balance& b); // one dynamic relaxation iteration
	void                                  syncShearMode(); // the law functor's shear mode: from the step's start, incremental in a fallback
	void                                  moveBodies(Real fraction); // by fraction x lineMove, through the velocities
	Real                                  residualMerit();           // |r| over the free DOFs, torques over the radius [N]; sets bodyRadius
	std::unique_ptr<ImplicitLinearSystem> sys; // not saved: rebuilt from the scene, it gives the same factor
};

} // namespace yade
