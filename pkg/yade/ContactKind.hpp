// SPDX-License-Identifier: GPL-2.0-or-later
// Parameters shared by all contacts of one kind (MORTAR, ITZ, AGG): YADE's face of the physics
// core's ContactKindParams (its table of per-kind parameters, SWELLDEM_KIND_PARAMETERS, becomes
// this class's Python attributes and saved fields). A kind holds settings only: what a run does
// with it (the step begun, the law built for it, the breaks) belongs to the run's law functor
// (KindLaws), so one kind may serve several scenes and ContactKind(**kind.dict()) is a full copy.
#pragma once
#include "compat/Plugin.hpp"
#include "core/ContactLaw.hpp"
#include <atomic>

namespace yade {

/// Errors met by swelldem's functors inside YADE's parallel loops, where nothing may throw: the
/// first one is kept here and raised by the log-time solvers after the loop (takeFunctorError).
void   recordFunctorError(const string& what);
string takeFunctorError();

class ContactKind : public Serializable {
public:
#define SWELLDEM_CONTACT_KIND_ATTRS(X)                                                                                                                         \
	X(string, name, "MORTAR", swelldem_attr::Setting, "Name of the kind (MORTAR, ITZ, AGG or any label) [-]")                                            \
	X(int, kindId, 0, swelldem_attr::Setting, "Index of the kind, reported per contact in SwellPhys.kindId (by convention 0 MORTAR, 1 ITZ, 2 AGG, 3 PLATEN, 4 STEEL, 5 BOND: swelldem.paper) [-]") \
	X(string, behaviour, "elastic", swelldem_attr::Setting,                                                                                              \
	  "'elastic' (constant modulus young), 'aging-elastic' (E(t) = 1/J(t + 0.01 d, t) of the B3 q's, incremental) "                                    \
	  "or 'viscoelastic' (aging, B3 solidification theory with a Kelvin chain) [-]")
	SWELLDEM_CLASS_WITH_TABLE(ContactKind, Serializable,
	                          "Parameters shared by all contacts of one kind (MORTAR, ITZ or AGG): stiffness, aging viscoelasticity (B3), "
	                          "swelling kinetics (Larive), a temperature history (Arrhenius kinetics, creep at temperature) and brittle "
	                          "strength. A change to a parameter during a run takes effect from the next physical step.",
	                          SWELLDEM_CONTACT_KIND_ATTRS, SWELLDEM_KIND_PARAMETERS)
	/// The per-kind parameters (all but behaviour), as the physics core takes them.
	swelldem::core::ContactKindParams table;

	ContactKind();
	virtual ~ContactKind() { }
	void postLoad();
	template <class C> static void pyMethods(C& cls)
	{
		cls.def("compliance", &ContactKind::compliance, "B3 J(t, t') of the kind's q's, t and t' in days [1/Pa].");
		cls.def("modulus", &ContactKind::modulus, "Modulus of the kind at age t [day]: young, or E(t) = 1/J(t + 0.01, t) for aging kinds [Pa].");
		cls.def("evaluateHistory", &ContactKind::evaluateHistory,
		        (boost::python::arg("times"), boost::python::arg("openings"), boost::python::arg("area"), boost::python::arg("length"),
		         boost::python::arg("swellDispInf") = -1.0),
		        "One contact of this kind alone, outside any scene: the physics core driven through physical times [day] "
		        "with imposed normal openings [m] (one per time, times[0] the stress-free state), facet area [m2] and length [m]; "
		        "returns the normal force [N] at each time (tension positive).");
		cls.def("setTemperatureHistory", &ContactKind::setTemperatureHistory, (boost::python::arg("days"), boost::python::arg("temperatures")),
		        "Sets temperatureDays [day] and temperatures [K] together (a history of another length cannot be set one "
		        "attribute at a time), validated; a refused history leaves the old one.");
	}

	/// The parameters with the behaviour, validated; the error names this kind.
	swelldem::core::ContactKindParams params() const;
	/// Counts the changes of the parameters (each accepted set from Python or load): a run's laws
	/// compare it with the one they were built from.
	long revision() const { return revision_.load(std::memory_order_acquire); }
	/// This object among all ContactKinds of the process (an address may be reused after a kind is gone).
	unsigned long instance() const { return instance_; }
	Real              compliance(Real t, Real tPrime) const;
	Real              modulus(Real t) const;
	void              setTemperatureHistory(const std::vector<Real>& days, const std::vector<Real>& temperatures);
	std::vector<Real> evaluateHistory(const std::vector<Real>& times, const std::vector<Real>& openings, Real area, Real length, Real swellDispInf) const;

private:
	std::atomic<long>   revision_ { 0 };
	const unsigned long instance_;
};

} // namespace yade
