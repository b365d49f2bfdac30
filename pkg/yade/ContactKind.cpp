// SPDX-License-Identifier: GPL-2.0-or-later
#include "ContactKind.hpp"
#include "core/B3Compliance.hpp"
#include "core/Validate.hpp"

namespace yade {
namespace core = swelldem::core;

core::ContactKindParams ContactKind::params() const
{
	core::ContactKindParams p;
	if (behaviour == "elastic") p.behaviour = core::Behaviour::Elastic;
	else if (behaviour == "aging-elastic")
		p.behaviour = core::Behaviour::AgingElastic;
	else if (behaviour == "viscoelastic")
		p.behaviour = core::Behaviour::Viscoelastic;
	else
		throw std::invalid_argument("swelldem: ContactKind(" + name + ").behaviour = '" + behaviour
		                            + "' is out of range; allowed: 'elastic', 'aging-elastic', 'viscoelastic'");
	p.contactModulus = young;
	p.shearRatio     = shearRatio;
	p.b3.q1          = q1;
	p.b3.q2          = q2;
	p.b3.q3          = q3;
	p.b3.q4          = q4;
	p.chain.unitsPerDecade        = kelvinUnitsPerDecade;
	p.swelling                    = swelling;
	p.swellingDisplacementInf     = swellDispInf;
	p.tauC                        = tauC;
	p.tauL                        = tauL;
	p.strength.damage             = damage;
	p.strength.tensileStrength    = tensileStrength;
	p.strength.shearFailure       = shearFailure;
	p.strength.cohesion           = cohesion;
	p.strength.frictionAngle      = frictionAngle;
	p.strength.residualFrictionAngle = residualFrictionAngle;
	return p;
}

void ContactKind::postLoad()
{
	// Validate now, with the kind's name in the message, so bad input fails before any work starts.
	try {
		params().validate();
	} catch (const std::invalid_argument& e) {
		throw std::invalid_argument(string(e.what()) + " (in ContactKind '" + name + "')");
	}
	std::lock_guard<std::mutex> lock(lawMutex_);
	law_.reset(); // parameters changed: the law is rebuilt on next use
}

void ContactKind::prepare(Real shortestLag, Real longestLag)
{
	std::lock_guard<std::mutex> lock(lawMutex_);
	try {
		law_ = std::make_unique<core::ContactLaw>(params(), shortestLag, longestLag);
	} catch (const std::invalid_argument& e) {
		throw std::invalid_argument(string(e.what()) + " (in ContactKind '" + name + "')");
	}
}

core::ContactLaw& ContactKind::law()
{
	if (!law_) {
		std::lock_guard<std::mutex> lock(lawMutex_);
		if (!law_) {
			law_ = std::make_unique<core::ContactLaw>(params(), 1e-2, 1e5);
			// Without the log-time integrator there is one open-ended step at age 28 days.
			law_->beginStep(28.0, 28.0);
		}
	}
	return *law_;
}

Real ContactKind::compliance(Real t, Real tPrime) const
{
	core::B3Params p;
	p.q1 = q1, p.q2 = q2, p.q3 = q3, p.q4 = q4;
	return core::B3Compliance(p).J(t, tPrime);
}

Real ContactKind::modulus(Real t) const
{
	if (behaviour == "elastic") return young;
	core::B3Params p;
	p.q1 = q1, p.q2 = q2, p.q3 = q3, p.q4 = q4;
	return core::B3Compliance(p).E(t);
}

int ContactKind::chainSize() { return law().creep() ? int(law().creep()->size()) : 0; }

} // namespace yade
