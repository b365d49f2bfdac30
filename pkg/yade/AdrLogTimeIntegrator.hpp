// SPDX-License-Identifier: GPL-2.0-or-later
// The paper's quasi-static solver, in place of NewtonIntegrator: each physical step of the
// log-time schedule (LogTimeSolver) is brought to equilibrium by adaptive dynamic relaxation
// (DynamicRelaxation).
#pragma once
#include "DynamicRelaxation.hpp"

namespace yade {

class AdrLogTimeIntegrator : public LogTimeSolver {
public:
#define SWELLDEM_ADR_ATTRS(X)                                                                                                                                  \
	X(Real, massSafety, DynamicRelaxation::kDefaultMassSafety, swelldem_attr::Setting,                                                                     \
	  "Factor on the Gershgorin bound of the fictitious masses (>= 1; at 1 an isolated pair of discs never settles) [-]")                                \
	X(Real, maxDamping, DynamicRelaxation::kDefaultMaxDamping, swelldem_attr::Setting, "Upper clamp of the ADR damping c dt (< 2) [-]")                                                 \
	X(bool, breakInIterations, false, swelldem_attr::Setting,                                                                                            \
	  "Break an overloaded contact at the iteration it is overloaded, in the relaxation's transients, as a dynamic-relaxation code does "      \
	  "unless told otherwise (the paper's ADR updates its masses when the stiffness changes, 'for example ... to damage'); false: every "   \
	  "break at equilibrium (breakOneAtATime applies then). A reading of the paper to measure, not a default (docs/scenarios.md) [-]")       \
	X(Real, damping, 0.0, swelldem_attr::Result, "ADR damping c dt of the last iteration [-]")                                                         \
	X(DynamicRelaxation, relaxation, DynamicRelaxation(), swelldem_attr::Internal, "Fictitious masses, previous residual and origin of the ADR [-]")
	SWELLDEM_CLASS(AdrLogTimeIntegrator, LogTimeSolver,
	               "Quasi-static log-time solver with adaptive dynamic relaxation for 2D swelldem scenes (discs in the plane z = 0 "
	               "with z translation and x, y rotations blocked); the paper's method. Replaces NewtonIntegrator; put it last in O.engines.",
	               SWELLDEM_ADR_ATTRS)
	virtual ~AdrLogTimeIntegrator() { }
	void action() override;
	void postLoad();
	template <class C> static void pyMethods(C&) { }
};

} // namespace yade
