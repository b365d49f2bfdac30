// SPDX-License-Identifier: GPL-2.0-or-later
// Parameters shared by all contacts of one kind (MORTAR, ITZ, AGG): YADE's face of the physics
// core's ContactKindParams (its table of per-kind parameters, SWELLDEM_KIND_PARAMETERS, becomes
// this class's Python attributes and saved fields), plus the core ContactLaw built from them.
// The law is not saved: the log-time solvers build it at their first step, a loaded kind rebuilds
// it on the step it was in, and a parameter changed during a run rebuilds it at the next step;
// under another integrator it is built at first use.
#pragma once
#include "compat/Plugin.hpp"
#include "core/ContactLaw.hpp"
#include <atomic>
#include <memory>
#include <mutex>

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
	  "or 'viscoelastic' (aging, B3 solidification theory with a Kelvin chain) [-]")                                                                   \
	X(long, breakEvents, 0, swelldem_attr::Result, "Contacts of this kind broken so far [-]")                                                            \
	X(long, stepSerial, 0, swelldem_attr::Result, "Physical steps begun on this kind; a contact sets itself up for a step when its own differs [-]")    \
	X(bool, breaksAtEquilibrium, false, swelldem_attr::Result,                                                                                           \
	  "Set by the log-time solvers: intact contacts break only at equilibrium; false under other integrators: the law breaks at once [-]")            \
	X(bool, shearFromStepStart, false, swelldem_attr::Result,                                                                                           \
	  "Set by ImplicitLogTimeSolver: the shear force is taken from the step's start (a broken contact's slip is decided by the state reached, "  \
	  "not by the iterations' path); false: YADE's incremental shear vector, whose slip is permanent at every iteration [-]")                      \
	X(Real, shortestLag, 1e-2, swelldem_attr::Result, "Shortest load duration the Kelvin chain resolves (set by the log-time solvers: first step) [day]") \
	X(Real, longestLag, 1e5, swelldem_attr::Result, "Longest load duration the Kelvin chain resolves (set by the log-time solvers: the run span) [day]") \
	X(Real, stepStart, 0.0, swelldem_attr::Internal, "Start of the physical step the law has begun (0: none) [day]")                                  \
	X(Real, stepEnd, 0.0, swelldem_attr::Internal, "End of the physical step the law has begun [day]")
	SWELLDEM_CLASS_WITH_TABLE(ContactKind, Serializable,
	                          "Parameters shared by all contacts of one kind (MORTAR, ITZ or AGG): stiffness, aging viscoelasticity (B3), "
	                          "swelling kinetics (Larive), a temperature history (Arrhenius kinetics, creep at temperature) and brittle "
	                          "strength. A change to a parameter during a run takes effect from the next physical step.",
	                          SWELLDEM_CONTACT_KIND_ATTRS, SWELLDEM_KIND_PARAMETERS)
	/// The per-kind parameters (all but behaviour), as the physics core takes them.
	swelldem::core::ContactKindParams table;

	ContactKind() { }
	virtual ~ContactKind() { }
	void postLoad();
	/// A saved kind comes back with its law begun on the step it was in, before any contact uses it.
	void afterLoad();
	template <class C> static void pyMethods(C& cls)
	{
		cls.def("compliance", &ContactKind::compliance, "B3 J(t, t') of the kind's q's, t and t' in days [1/Pa].");
		cls.def("modulus", &ContactKind::modulus, "Modulus of the kind at age t [day]: young, or E(t) = 1/J(t + 0.01, t) for aging kinds [Pa].");
		cls.def("chainSize", &ContactKind::chainSize, "Number of Kelvin units per direction of the kind's law (0 unless viscoelastic) [-].");
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
	/// Log-time solvers, at a step's start (outside any parallel region): (re)builds the law when
	/// there is none, the lags changed or a parameter changed since it was built, then begins the
	/// step [tPrev, t] [day]. Throws std::invalid_argument for bad parameters or a Kelvin chain
	/// that would change under contacts with a creep history.
	void beginStep(Real shortestLag, Real longestLag, Real tPrev, Real t);
	/// The law for the contacts (thread-safe); under another integrator it is built at first use
	/// and after a parameter changed, with one open-ended step at age 28 days. Throws
	/// std::invalid_argument for bad parameters.
	swelldem::core::ContactLaw& law();
	Real              compliance(Real t, Real tPrime) const;
	Real              modulus(Real t) const;
	int               chainSize();
	void              setTemperatureHistory(const std::vector<Real>& days, const std::vector<Real>& temperatures);
	std::vector<Real> evaluateHistory(const std::vector<Real>& times, const std::vector<Real>& openings, Real area, Real length, Real swellDispInf) const;

private:
	std::unique_ptr<swelldem::core::ContactLaw>              law_;
	std::vector<std::unique_ptr<swelldem::core::ContactLaw>> retired_; // a replaced law may still be read by a running loop
	std::atomic<swelldem::core::ContactLaw*>                 lawReady_ { nullptr };
	std::mutex                                               lawMutex_;
	std::atomic<bool>                                        changed_ { false }; // a parameter was set since the law was built
	void install(std::unique_ptr<swelldem::core::ContactLaw> law);
};

} // namespace yade
