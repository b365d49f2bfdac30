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

core::ContactKindParams ContactKind::checkedParams() const
{
	try {
		core::ContactKindParams p = params();
		p.validate();
		return p;
	} catch (const std::invalid_argument& e) {
		throw std::invalid_argument(string(e.what()) + " (in ContactKind '" + name + "')");
	}
}

void ContactKind::postLoad()
{
	checkedParams(); // bad input fails here, before any work starts
	std::lock_guard<std::mutex> lock(lawMutex_);
	lawReady_.store(nullptr, std::memory_order_release);
	law_.reset(); // parameters changed: the law is rebuilt on next use
}

void ContactKind::prepare(Real shortestLag, Real longestLag)
{
	std::lock_guard<std::mutex> lock(lawMutex_);
	this->shortestLag = shortestLag;
	this->longestLag  = longestLag;
	law_ = std::make_unique<core::ContactLaw>(checkedParams(), shortestLag, longestLag);
	lawReady_.store(law_.get(), std::memory_order_release);
}

core::ContactLaw& ContactKind::law()
{
	// Contacts call this from InteractionLoop's threads; the law is built once, under the lock.
	if (core::ContactLaw* ready = lawReady_.load(std::memory_order_acquire)) return *ready;
	std::lock_guard<std::mutex> lock(lawMutex_);
	if (!law_) {
		law_ = std::make_unique<core::ContactLaw>(checkedParams(), shortestLag, longestLag);
		// Without the log-time integrator there is one open-ended step at age 28 days; after
		// O.load the integrator begins its current step again before any contact commits.
		law_->beginStep(28.0, 28.0);
	}
	lawReady_.store(law_.get(), std::memory_order_release);
	return *law_;
}

Real ContactKind::compliance(Real t, Real tPrime) const { return core::B3Compliance(params().b3).J(t, tPrime); }

Real ContactKind::modulus(Real t) const { return behaviour == "elastic" ? young : core::B3Compliance(params().b3).E(t); }

std::vector<Real>
ContactKind::evaluateHistory(const std::vector<Real>& times, const std::vector<Real>& openings, Real area, Real length, Real swellDispInf) const
{
	core::require(times.size() >= 2, "ContactKind.evaluateHistory: len(times)", double(times.size()), ">= 2");
	core::require(openings.size() == times.size(), "ContactKind.evaluateHistory: len(openings)", double(openings.size()), "len(times)");
	core::ContactLaw      law(params(), times[1] - times[0], times.back() - times.front());
	core::ContactGeometry g;
	g.area = area, g.length = length, g.swellingDisplacementInf = swellDispInf;
	core::ContactState s;
	law.initState(s);
	std::vector<Real> F(1, 0.0);
	for (size_t i = 1; i < times.size(); ++i) {
		law.beginStep(times[i - 1], times[i]);
		law.beginContactStep(g, s);
		law.trial(g, s, openings[i] - openings[i - 1], 0.0);
		law.commit(g, s);
		F.push_back(s.committed.Fn);
	}
	return F;
}

int ContactKind::chainSize() { return law().creep() ? int(law().creep()->size()) : 0; }

} // namespace yade
