// SPDX-License-Identifier: GPL-2.0-or-later
#include "ContactKind.hpp"
#include "core/B3Compliance.hpp"
#include "core/Validate.hpp"

namespace yade {
namespace core = swelldem::core;

core::ContactKindParams ContactKind::params() const
{
	try {
		core::ContactKindParams p = table;
		p.behaviour               = core::parseBehaviour(behaviour);
		p.validate();
		return p;
	} catch (const std::invalid_argument& e) {
		throw std::invalid_argument(string(e.what()) + " (in ContactKind '" + name + "')");
	}
}

namespace {
	std::atomic<unsigned long> kindsMade { 0 };
}

ContactKind::ContactKind() : instance_(++kindsMade) { }

void ContactKind::postLoad()
{
	params(); // bad input fails here, before any work starts
	revision_.fetch_add(1, std::memory_order_acq_rel);
}

namespace {
	std::mutex functorErrorMutex;
	string     functorError;
}

void recordFunctorError(const string& what)
{
	std::lock_guard<std::mutex> lock(functorErrorMutex);
	if (functorError.empty()) functorError = what;
}

string takeFunctorError()
{
	std::lock_guard<std::mutex> lock(functorErrorMutex);
	string e;
	e.swap(functorError);
	return e;
}

Real ContactKind::compliance(Real t, Real tPrime) const { return core::B3Compliance(table.b3).J(t, tPrime); }

Real ContactKind::modulus(Real t) const { return behaviour == "elastic" ? table.contactModulus : core::B3Compliance(table.b3).E(t); }

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

void ContactKind::setTemperatureHistory(const std::vector<Real>& days, const std::vector<Real>& temperatures)
{
	std::vector<double> oldDays = table.temperatureDays, oldTemps = table.temperatures;
	table.temperatureDays       = std::vector<double>(days.begin(), days.end());
	table.temperatures          = std::vector<double>(temperatures.begin(), temperatures.end());
	try {
		postLoad();
	} catch (const std::exception& e) {
		table.temperatureDays = std::move(oldDays);
		table.temperatures    = std::move(oldTemps);
		throw std::invalid_argument(string("ContactKind.setTemperatureHistory refused, the old history kept: ") + e.what());
	}
}

} // namespace yade
