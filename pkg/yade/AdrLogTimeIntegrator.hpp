// SPDX-License-Identifier: GPL-2.0-or-later
// The paper's quasi-static solver, in place of NewtonIntegrator: each physical step of the
// log-time schedule (LogTimeSolver) is brought to equilibrium by adaptive dynamic relaxation
// (Underwood): fictitious masses from a Gershgorin bound of the contact stiffness, damping from a
// Rayleigh quotient of a local stiffness estimate, a damped leapfrog step per iteration.
#pragma once
#include "LogTimeSolver.hpp"

namespace yade {

class AdrLogTimeIntegrator : public LogTimeSolver {
public:
#define SWELLDEM_ADR_ATTRS(X)                                                                                                                                  \
	X(Real, massSafety, 1.0, swelldem_attr::Setting, "Factor on the Gershgorin bound of the fictitious masses (>= 1) [-]")                             \
	X(Real, maxDamping, 1.8, swelldem_attr::Setting, "Upper clamp of the ADR damping c dt (< 2) [-]")                                                 \
	X(Real, damping, 0.0, swelldem_attr::Result, "ADR damping c dt of the last iteration [-]")                                                         \
	X(std::vector<Real>, massX, std::vector<Real>(), swelldem_attr::Internal, "Fictitious mass per body, x [kg-equivalent]")                          \
	X(std::vector<Real>, massY, std::vector<Real>(), swelldem_attr::Internal, "Fictitious mass per body, y [kg-equivalent]")                          \
	X(std::vector<Real>, inertiaZ, std::vector<Real>(), swelldem_attr::Internal, "Fictitious rotational inertia per body [kg m2-equivalent]")         \
	X(std::vector<Real>, prevForce, std::vector<Real>(), swelldem_attr::Internal, "Residual force of the previous iteration, 3 per body (x, y, torque z)") \
	X(std::vector<Real>, initialPos, std::vector<Real>(), swelldem_attr::Internal, "Positions at the start, 2 per body, for the damping estimate [m]")  \
	X(long, nContactsSeen, -1, swelldem_attr::Internal, "Real contacts when the masses were last computed [-]")
	SWELLDEM_CLASS(AdrLogTimeIntegrator, LogTimeSolver,
	               "Quasi-static log-time solver with adaptive dynamic relaxation for 2D swelldem scenes (discs in the plane z = 0 "
	               "with z translation and x, y rotations blocked); the paper's method. Replaces NewtonIntegrator; put it last in O.engines.",
	               SWELLDEM_ADR_ATTRS)
	virtual ~AdrLogTimeIntegrator() { }
	void action() override;
	void postLoad();
	template <class C> static void pyMethods(C&) { }

private:
	void start();
	void computeMasses();
	Real dampingEstimate() const;
	void leapfrog(Real c);
};

} // namespace yade
