// SPDX-License-Identifier: GPL-2.0-or-later
// What swelldem's quasi-static solvers share, whatever their equilibrium method: physical (creep)
// times evenly spaced in log time, the contacts' step set-up (each kind begins the step; each
// contact sets itself up at its first iteration of it) and commit, breaks at equilibrium, the
// unbalanced-force ratio that decides equilibrium, the per-step hook, progress lines and O.save /
// O.load. One YADE iteration is one equilibrium iteration; O.dt is a pseudo time step (1).
// AdrLogTimeIntegrator (adaptive dynamic relaxation, the paper's method) and ImplicitLogTimeSolver
// (Newton iterations with a sparse Cholesky factor) derive from it and implement action() with
// the helpers below. Imposed displacements: move a held body (blockedDOFs x or y) by setting its
// position, e.g. in the stepHook; constant loads: YADE's ForceEngine or O.forces.setPermF; a body
// held elastically (a partially restrained platen): springBodies. A scene is 2D (discs in the plane z = 0, z translation
// and x, y rotations blocked) or 3D (spheres, six DOFs a body): nDim.
#pragma once
#include <functional>
#include "Law2_ScGeom_SwellPhys_AgingSwelling.hpp"
#include <chrono>

namespace yade {

class LogTimeSolver : public GlobalEngine {
public:
#define SWELLDEM_LOG_TIME_ATTRS(X)                                                                                                                             \
	X(Real, tStart, 1.0, swelldem_attr::Setting, "Physical time (age) of the initial, stress-free state [day]")                                          \
	X(Real, tEnd, 3650.0, swelldem_attr::Setting, "Last physical time [day]")                                                                            \
	X(Real, stepsPerDecade, 10, swelldem_attr::Setting, "Physical steps per decade of log time (0 < N <= 10000) [1/decade]")                          \
	X(std::vector<Real>, extraTimes, std::vector<Real>(), swelldem_attr::Setting, "Additional physical times to stop at (e.g. output times) [day]")   \
	X(Real, tolerance, 1e-4, swelldem_attr::Setting,                                                                                                     \
	  "Equilibrium when the unbalanced-force ratio is below: mean resultant force on free bodies / mean contact force, a contact "                    \
	  "counting at least with the load its step offset imposes, kn'' |du''| + ks'' |du_s''|, and external loads counting too [-]")                   \
	X(long, minIterations, 2, swelldem_attr::Setting, "Iterations per physical step at least [-]")                                                     \
	X(long, maxIterations, 200000, swelldem_attr::Setting,                                                                                               \
	  "Iterations to an equilibrium at most, counted from the step's start and again after each round of breaks; beyond, the run stops "         \
	  "with a message [-]")                                                                                                                          \
	X(Real, divergenceRatio, 1e6, swelldem_attr::Setting, "An unbalanced-force ratio above this (or NaN) stops the run as diverged [-]")               \
	X(Real, relativeForceFloor, 1e-3, swelldem_attr::Setting,                                                                                            \
	  "The mean contact force of the ratio is at least this fraction of its largest value in the run [-]")                                           \
	X(long, colliderPeriod, 20, swelldem_attr::Setting,                                                                                                  \
	  "Run the engine labelled colliderLabel only every this many iterations and at each step's start (1: always) [-]")                              \
	X(string, colliderLabel, "collider", swelldem_attr::Setting, "Label of the collider engine that colliderPeriod controls [-]")                      \
	X(bool, breakOneAtATime, false, swelldem_attr::Setting,                                                                                              \
	  "At each equilibrium break only the most overloaded contact, then iterate again (sequentially linear analysis), instead of every "       \
	  "overloaded contact at once; for measuring what the break rule changes (docs/performance.md) [-]")                                           \
	X(std::vector<int>, springBodies, std::vector<int>(), swelldem_attr::Setting,                                                                       \
	  "Bodies held by a linear spring to where they are at the run's start, along springAxes (a platen under partial restraint) [-]")             \
	X(std::vector<int>, springAxes, std::vector<int>(), swelldem_attr::Setting, "Axis of each spring: 0 x, 1 y, 2 z (3D) [-]")                                  \
	X(std::vector<Real>, springStiffness, std::vector<Real>(), swelldem_attr::Setting, "Stiffness of each spring, >= 0 [N/m]")                      \
	X(bool, verbose, true, swelldem_attr::Setting, "Print a progress line per physical step [-]")                                                      \
	X(long, historyEvery, 20, swelldem_attr::Setting,                                                                                                    \
	  "Iterations between two records of the unbalanced-force history (historyIteration, historyUnbalanced); the first and the last "           \
	  "iteration of every physical step are recorded as well; 0: no history [-]")                                                                  \
	X(std::vector<Real>, times, std::vector<Real>(), swelldem_attr::Result, "Physical times of the run, tStart first (set at the first iteration) [day]") \
	X(int, step, 0, swelldem_attr::Result, "Current physical step (1..nSteps; step i goes from times[i-1] to times[i]) [-]")                           \
	X(Real, physTime, 0.0, swelldem_attr::Result, "Physical time reached by the last converged step [day]")                                            \
	X(long, iterInStep, 0, swelldem_attr::Result, "Iterations in the current physical step [-]")                                                       \
	X(long, totalIterations, 0, swelldem_attr::Result, "Iterations since the start [-]")                                                               \
	X(Real, unbalanced, 0.0, swelldem_attr::Result, "Unbalanced-force ratio of the last iteration [-]")                                                \
	X(bool, finished, false, swelldem_attr::Result, "True once the last physical step has converged [-]")                                             \
	X(std::vector<Real>, stepIterations, std::vector<Real>(), swelldem_attr::Result, "Iterations of each converged step [-]")                         \
	X(std::vector<Real>, stepUnbalanced, std::vector<Real>(), swelldem_attr::Result, "Unbalanced-force ratio at the end of each converged step [-]")  \
	X(std::vector<Real>, stepRoundOff, std::vector<Real>(), swelldem_attr::Result,                                                                      \
	  "1 where a step ended above the tolerance: at the positions' round-off limit (stepRoundOffRatio), or above it where the implicit " \
	  "solver settled the step by relaxation (stallTolerance, fallbackTolerance); else 0 [-]")                                                \
	X(std::vector<Real>, stepRoundOffRatio, std::vector<Real>(), swelldem_attr::Result,                                                                 \
	  "Unbalanced-force ratio of the positions' round-off limit at the end of each converged step (256 machine epsilons of the "             \
	  "largest coordinate times the mean contact stiffness, over the mean contact force): no equilibrium is resolved below it [-]")       \
	X(std::vector<Real>, stepWall, std::vector<Real>(), swelldem_attr::Result, "Wall time at the end of each converged step since the start [s]")    \
	X(std::vector<Real>, historyIteration, std::vector<Real>(), swelldem_attr::Result,                                                                  \
	  "Cumulative iteration (totalIterations) of each record of the unbalanced-force history (historyEvery) [-]")                                   \
	X(std::vector<Real>, historyUnbalanced, std::vector<Real>(), swelldem_attr::Result,                                                                 \
	  "Unbalanced-force ratio at each record of the history, at the iteration historyIteration of the same index [-]")                           \
	X(long, brokenSeen, 0, swelldem_attr::Result, "Break events seen so far (the law functor's nBreaks) [-]")                                                     \
	X(long, roundStart, 0, swelldem_attr::Internal, "Iteration of the step at which the last round of breaks happened [-]")                          \
	X(Real, forceScaleMax, 0.0, swelldem_attr::Internal, "Largest mean contact force of the run so far [N]")                                          \
	X(Real, externalScale, 0.0, swelldem_attr::Internal, "Mean external load on the free bodies, measured at the step's first iteration [N]")        \
	X(long, nRealSeen, -1, swelldem_attr::Internal, "Real contacts at the last iteration [-]")                                                        \
	X(int, nDim, 2, swelldem_attr::Result,                                                                                                                \
	  "Dimension of the scene, from its bodies at the start: 2 (discs: z translation and x, y rotations blocked) or 3 (spheres) [-]")            \
	X(std::vector<Real>, heldPos, std::vector<Real>(), swelldem_attr::Internal, "Positions (x, y; z in 3D) of the bodies at the end of the last action [m]")  \
	X(std::vector<Real>, springAnchors, std::vector<Real>(), swelldem_attr::Internal, "Position of each spring's body at the run's start [m]")      \
	X(Real, wallBefore, 0.0, swelldem_attr::Internal, "Wall time of the run before this session (O.load) [s]")
	SWELLDEM_CLASS(LogTimeSolver, GlobalEngine,
	               "Base of swelldem's quasi-static log-time solvers (AdrLogTimeIntegrator, ImplicitLogTimeSolver); not usable "
	               "alone.",
	               SWELLDEM_LOG_TIME_ATTRS)
	virtual ~LogTimeSolver();
	void action() override;
	void postLoad();
	void afterLoad();
	template <class C> static void pyMethods(C& cls)
	{
		cls.add_property("nSteps", &LogTimeSolver::nSteps, "Number of physical steps [-]");
		cls.add_property("plannedTimes", &LogTimeSolver::plannedTimes,
		                 "Physical times the schedule settings (tStart, tEnd, stepsPerDecade, extraTimes) give, tStart first: what "
		                 "times will hold once the run starts, known before it (e.g. to compute a field on the steps ahead) [day]");
		cls.def("checkMpiRanks", &LogTimeSolver::checkMpiRanks,
		        "Raises ValueError when the process runs under mpirun -n P (P > 1) and this solver, as set, would leave the "
		        "ranks above 0 idle: only ImplicitLogTimeSolver with linearSolver 'auto', 'petsc-gamg' or 'petsc-mumps' shares its work "
		        "(the linear solves) with them, and a run continued after O.load keeps the linear solver it started with. The run checks it at its start "
		        "and at its first iteration after O.load; a script calls it to refuse earlier.");
		cls.add_property("stepHook", &LogTimeSolver::getStepHook, &LogTimeSolver::setStepHook,
		                 "Python callable run without arguments after every converged physical step, or None. Not saved "
		                 "with the scene: set it again after O.load [-]");
	}
	std::vector<Real>     plannedTimes() const;
	void                  checkMpiRanks() const;
	int                   nSteps() const { return times.empty() ? 0 : int(times.size()) - 1; }
	static const long     kParallelBodies = 4000; // below this many discs a loop is cheaper than waking OpenMP's threads
	/// The blocked-DOF bit of each translation and rotation axis.
	static constexpr unsigned kAxisDOF[3] = { State::DOF_X, State::DOF_Y, State::DOF_Z };
	static constexpr unsigned kRotDOF[3]  = { State::DOF_RX, State::DOF_RY, State::DOF_RZ };
	boost::python::object getStepHook() const;
	void                  setStepHook(const boost::python::object& hook);

protected:
	/// Equilibrium measure of the current iteration (after the InteractionLoop).
	struct Balance {
		Real ratio      = 0;     // unbalanced-force ratio
		bool atRoundOff = false; // below what the positions' round-off can resolve
		Real roundOff   = 0;     // the ratio at that limit
		long nReal      = 0;     // real contacts
	};
	enum class StepOutcome { Continue, Broke, Committed };

	/// Start of every action(): set-up at the first call, re-begins the step after O.load, raises
	/// errors recorded by the functors; false when the call has nothing more to do.
	bool startIteration();
	Balance measureBalance();
	/// Commits the step when it is in equilibrium (converged) with no overloaded contact; breaks
	/// the overloaded ones otherwise (Broke); stops the run when it diverged or ran out of iterations.
	StepOutcome settleStep(const Balance& b, bool converged);
	/// End of every action(): a body held in x or y that was moved since the last action (by the
	/// stepHook or between O.run calls) gets the velocity of that move for one pass, so that YADE's
	/// contact geometry, which integrates the shear from velocities, sees it as a displacement.
	void trackHeldBodies();
	/// Adds each spring's stiffness to the diagonal entry of its body's axis: stiff(body id, axis, k).
	template <class F> void forEachSpring(F stiff) const
	{
		for (size_t i = 0; i < springBodies.size(); ++i)
			stiff(springBodies[i], springAxes[i], springStiffness[i]);
	}
	/// Calls trackHeldBodies() at every exit of an action() after startIteration().
	struct TrackHeldBodiesAtExit {
		LogTimeSolver* self;
		~TrackHeldBodiesAtExit() { self->trackHeldBodies(); }
	};
	[[noreturn]] void fail(const string& why) const;
	double            wallNow() const; // [s] of the run, sessions before an O.load included
	static void       zeroVelocities(Scene* scene);
	static const unsigned kNeed2D = State::DOF_Z | State::DOF_RX | State::DOF_RY;
	static constexpr unsigned kAllDOF = State::DOF_X | State::DOF_Y | State::DOF_Z | State::DOF_RX | State::DOF_RY | State::DOF_RZ;
	std::vector<const ContactKind*>      kinds;                      // the kinds of the scene's contacts, refreshed when contacts come or go
	Law2_ScGeom_SwellPhys_AgingSwelling* law2               = nullptr; // the scene's law functor (owns the run's laws), found at the start and after O.load
	const char*                          iterationName      = "ADR";   // what one iteration is, for the progress lines
	bool                                 shearFromStepStart = false;   // the law functor's mode this solver sets
	/// What a solver adds to the progress line about its own iterations (not virtual: the vtable
	/// must keep the size of the stock engine's, compat/abi_pairs.txt).
	std::function<std::string()> progressDetail;
	/// Called when a step is about to be committed (before the progress line and the stepHook), so
	/// that a solver records its own per-step results where the hook reads them.
	std::function<void()> beforeCommit;
	/// Whether the run, as set, takes part in the MPI ranks above 0 (mpirun -n P): only PETSc's
	/// linear solves do; a run that would leave them idle is refused at its start.
	std::function<bool()> sharesRanks;

private:
	void   initialize();
	void   beginPhysicalStep();
	void   commitPhysicalStep();
	void   refreshKinds();
	void   findLaw(); // law2, and the modes this solver sets on it
	long   breakOverloaded();
	void   controlCollider();
	void   measureExternalScale(long nFree);
	void   applySprings();
	void   runStepHook();
	void   recordHistory();
	void   progressLine() const;
	void   longStepLine(const Balance& b);
	double longStepShown = 0; // [s] wallNow() of the last line of a long step (0: none in this step)
	std::chrono::steady_clock::time_point  sessionStart = std::chrono::steady_clock::now();
	bool                                   kindsStale   = true; // the list of kinds and law2 are not saved: found again after O.load
	std::unique_ptr<boost::python::object> stepHook_;           // null: no hook (holds a Python reference: released under the GIL)
};

} // namespace yade
