// SPDX-License-Identifier: GPL-2.0-or-later
// Quasi-static solver of swelldem, in place of NewtonIntegrator: physical (creep) times evenly
// spaced in log time, each brought to equilibrium by adaptive dynamic relaxation (Underwood):
// fictitious masses from a Gershgorin bound of the contact stiffness, damping from a Rayleigh
// quotient of a local stiffness estimate. One YADE iteration is one ADR iteration; O.dt is the
// ADR pseudo time step (1). Contacts break during the iterations; the step is accepted only when
// an iteration without new breaks is in equilibrium; then every contact commits its hidden state.
#pragma once
#include "Law2_ScGeom_SwellPhys_AgingSwelling.hpp"
#include <chrono>

namespace yade {

class AdrLogTimeIntegrator : public GlobalEngine {
public:
#define SWELLDEM_ADR_ATTRS(X)                                                                                                                                  \
	X(Real, tStart, 1.0, "Physical time (age) of the initial, stress-free state [day]")                                                                  \
	X(Real, tEnd, 3650.0, "Last physical time [day]")                                                                                                     \
	X(Real, stepsPerDecade, 10, "Physical steps per decade of log time [1/decade]")                                                                     \
	X(std::vector<Real>, extraTimes, std::vector<Real>(), "Additional physical times to stop at (e.g. output times) [day]")                             \
	X(Real, tolerance, 1e-4, "Equilibrium when the unbalanced-force ratio is below: mean resultant force on free bodies / mean contact force, a contact "  \
	                                "counting at least with the load its step offset imposes, kn'' |du''| + ks'' |du_s''| [-]")    \
	X(long, minIterations, 2, "ADR iterations per physical step at least [-]")                                                                          \
	X(long, maxIterations, 200000, "ADR iterations per physical step at most; beyond, the run stops with a message [-]")                               \
	X(Real, massSafety, 1.0, "Factor on the Gershgorin bound of the fictitious masses (>= 1) [-]")                                                     \
	X(Real, maxDamping, 1.8, "Upper clamp of the ADR damping c dt (< 2) [-]")                                                                          \
	X(Real, divergenceRatio, 1e6, "An unbalanced-force ratio above this (or NaN) stops the run as diverged [-]")                                      \
	X(Real, relativeForceFloor, 1e-3, "The mean contact force of the ratio is at least this fraction of its largest value in the run [-]")      \
	X(Real, forceScaleMax, 0.0, "Largest mean contact force of the run so far [N] (internal)")                                                   \
	X(long, colliderPeriod, 20, "Run the engine labelled colliderLabel only every this many ADR iterations and at each step's start (1: always) [-]") \
	X(string, colliderLabel, "collider", "Label of the collider engine that colliderPeriod controls [-]")                                        \
	X(bool, verbose, true, "Print a progress line per physical step [-]")                                                                             \
	X(std::vector<Real>, times, std::vector<Real>(), "Physical times of the run, tStart first (set at the first iteration) [day]")                    \
	X(int, step, 0, "Current physical step (1..nSteps; step i goes from times[i-1] to times[i]) [-]")                                                  \
	X(Real, physTime, 0.0, "Physical time reached by the last converged step [day]")                                                                   \
	X(long, iterInStep, 0, "ADR iterations in the current physical step [-]")                                                                          \
	X(long, totalIterations, 0, "ADR iterations since the start [-]")                                                                                  \
	X(Real, unbalanced, 0.0, "Unbalanced-force ratio of the last iteration [-]")                                                                       \
	X(Real, damping, 0.0, "ADR damping c dt of the last iteration [-]")                                                                                \
	X(bool, finished, false, "True once the last physical step has converged [-]")                                                                    \
	X(std::vector<Real>, stepIterations, std::vector<Real>(), "ADR iterations of each converged step [-]")                                            \
	X(std::vector<Real>, stepUnbalanced, std::vector<Real>(), "Unbalanced-force ratio at the end of each converged step [-]")                         \
	X(std::vector<Real>, stepRoundOff, std::vector<Real>(), "1 where a step ended at the round-off limit of the positions above the tolerance, else 0 [-]") \
	X(std::vector<Real>, stepWall, std::vector<Real>(), "Wall time at the end of each converged step since the start [s]")                            \
	X(long, brokenSeen, 0, "Break events seen so far (sum over kinds) [-]")                                                                            \
	X(std::vector<Real>, massX, std::vector<Real>(), "Fictitious mass per body, x [kg-equivalent] (internal)")                                        \
	X(std::vector<Real>, massY, std::vector<Real>(), "Fictitious mass per body, y (internal)")                                                          \
	X(std::vector<Real>, inertiaZ, std::vector<Real>(), "Fictitious rotational inertia per body (internal)")                                           \
	X(std::vector<Real>, prevForce, std::vector<Real>(), "Residual force of the previous iteration, 3 per body (x, y, torque z) (internal)")           \
	X(std::vector<Real>, initialPos, std::vector<Real>(), "Positions at the start, 2 per body, for the damping estimate (internal)")                    \
	X(long, nContactsSeen, -1, "Real contacts when the masses were last computed (internal) [-]")                                                      \
	X(Real, wallBefore, 0.0, "Wall time of earlier sessions of this run (kept across O.save/O.load) [s]")
	SWELLDEM_CLASS(AdrLogTimeIntegrator, GlobalEngine,
	               "Quasi-static log-time solver with adaptive dynamic relaxation for 2D swelldem scenes (discs in the plane z = 0 "
	               "with z translation and x, y rotations blocked). Replaces NewtonIntegrator; put it last in O.engines.",
	               SWELLDEM_ADR_ATTRS)
	virtual ~AdrLogTimeIntegrator();
	void action() override;
	void postLoad();
	template <class C> static void pyMethods(C& cls)
	{
		cls.add_property("nSteps", &AdrLogTimeIntegrator::nSteps, "Number of physical steps [-]");
		cls.add_property("stepHook", &AdrLogTimeIntegrator::getStepHook, &AdrLogTimeIntegrator::setStepHook,
		                 "Python callable run without arguments after every converged physical step, or None. Not saved "
		                 "with the scene: set it again after O.load [-]");
	}
	boost::python::object getStepHook() const;
	void                  setStepHook(const boost::python::object& hook);
	int nSteps() const { return times.empty() ? 0 : int(times.size()) - 1; }

private:
	void                      initialize();
	void                      beginPhysicalStep();
	void                      commitPhysicalStep();
	void                      computeMasses();
	std::vector<ContactKind*> kindsInScene() const;
	long                      breakEvents() const;
	void                      refreshKinds();    // kinds = kindsInScene(), each set to break at equilibrium only
	long                      breakOverloaded(); // at equilibrium: breaks the overloaded contacts, returns how many
	void                      controlCollider();
	std::vector<ContactKind*> kinds; // the kinds of the scene's contacts, refreshed when contacts come or go
	[[noreturn]] void         fail(const string& why) const;
	double                    wallNow() const;
	std::chrono::steady_clock::time_point sessionStart = std::chrono::steady_clock::now();
	std::unique_ptr<boost::python::object> stepHook_; // null: no hook (holds a Python reference: released under the GIL)
	bool rebeginStep = true; // the kinds' laws are not serialized: begin the current step again after O.load
};

} // namespace yade
