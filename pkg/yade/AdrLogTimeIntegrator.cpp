// SPDX-License-Identifier: GPL-2.0-or-later
#include "AdrLogTimeIntegrator.hpp"
#include "core/Validate.hpp"

namespace yade {
namespace core = swelldem::core;

void AdrLogTimeIntegrator::postLoad()
{
	LogTimeSolver::postLoad();
	core::require(massSafety >= 1, "AdrLogTimeIntegrator.massSafety", massSafety, ">= 1");
	core::requireOpenInterval("AdrLogTimeIntegrator.maxDamping", maxDamping, 0, 2);
}

void AdrLogTimeIntegrator::action()
{
	const bool starting = times.empty();
	if (!startIteration()) {
		if (starting && !times.empty()) relaxation.start(scene, nDim);
		return;
	}
	// the law reads this at every contact of the next iteration; set here, it also holds after O.load
	law2->breaksAtEquilibrium = !breakInIterations;
	const TrackHeldBodiesAtExit track { this };
	const Balance b = measureBalance();
	// A break leaves kn, ks (and so the Gershgorin bound) as they are: only new or lost contacts
	// and a new step's stiffness call for new masses.
	if (b.nReal != relaxation.nContactsSeen || iterInStep == 1 || relaxation.massX.size() != scene->bodies->body.size()) {
		relaxation.computeMasses(scene, massSafety);
		forEachSpring([this](int id, int axis, Real k) { relaxation.addStiffness(scene, massSafety, id, axis, k); });
	}
	if (settleStep(b, b.ratio <= tolerance || b.atRoundOff) == StepOutcome::Committed) {
		relaxation.rest();
		return;
	}
	const Real c = relaxation.damping(scene, maxDamping);
	damping      = c * scene->dt;
	relaxation.leapfrog(scene, c);
}

} // namespace yade
