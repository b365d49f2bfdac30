// SPDX-License-Identifier: GPL-2.0-or-later
// Parameters shared by all contacts of one kind (MORTAR, ITZ, AGG): YADE's face of the physics
// core's ContactKindParams, plus the core ContactLaw built from them (not serialized: rebuilt on load).
// Every SwellPhys points to its kind; AdrLogTimeIntegrator starts each physical step on each kind.
#pragma once
#include "compat/Plugin.hpp"
#include "core/ContactLaw.hpp"
#include <atomic>
#include <memory>
#include <mutex>

namespace yade {

class ContactKind : public Serializable {
public:
#define SWELLDEM_CONTACT_KIND_ATTRS(X)                                                                                                                         \
	X(string, name, "MORTAR", "Name of the kind (MORTAR, ITZ, AGG or any label) [-]")                                                                      \
	X(int, kindId, 0, "Index of the kind, reported per contact in SwellPhys.kindId (0 MORTAR, 1 ITZ, 2 AGG by convention) [-]")                         \
	X(string, behaviour, "elastic", "'elastic' (constant modulus young), 'aging-elastic' (E(t) = 1/J(t + 0.01 d, t) of the B3 q's, incremental) "        \
	                                "or 'viscoelastic' (aging, B3 solidification theory with a Kelvin chain) [-]")                                        \
	X(Real, young, 30e9, "Contact modulus E_c of 'elastic' kinds; kn = E_c A / L [Pa]")                                                                  \
	X(Real, shearRatio, 0.3, "alpha = ks / kn [-]")                                                                                                        \
	X(Real, q1, 6.7e-12, "B3 instantaneous compliance q1 [1/Pa] (paper Table 3.3: 1e-6/MPa = 1e-12/Pa)")                                                  \
	X(Real, q2, 108.1e-12, "B3 aging viscoelastic compliance q2 [1/Pa]")                                                                                   \
	X(Real, q3, 44.2e-12, "B3 non-aging viscoelastic compliance q3 [1/Pa]")                                                                                \
	X(Real, q4, 14.3e-12, "B3 flow compliance q4 [1/Pa]")                                                                                                  \
	X(Real, kelvinUnitsPerDecade, 1.0, "Kelvin units per decade of retardation time (cost against accuracy) [1/decade]")                                  \
	X(Real, swellDispInf, 0.0, "Ultimate free swelling displacement d_inf of the kind's contacts (0: none; per-contact override "                         \
	                           "SwellPhys.swellDispInf) [m]")                                                                                              \
	X(Real, tauC, 50.0, "Larive characteristic time tau_c [day]")                                                                                          \
	X(Real, tauL, 100.0, "Larive latency time tau_L [day]")                                                                                                \
	X(bool, swelling, false, "Evaluate swelling kinetics for this kind (set when any of its contacts swells) [-]")                                       \
	X(bool, damage, false, "Brittle failure on: tension cut-off f_t A, optional Mohr-Coulomb shear failure [-]")                                          \
	X(Real, tensileStrength, 4e6, "f_t; a contact breaks when Fn > f_t A [Pa]")                                                                           \
	X(bool, shearFailure, false, "Mohr-Coulomb shear failure of intact contacts, |Fs| > c A + tan(phi) max(-Fn, 0) (the paper keeps it off) [-]")       \
	X(Real, cohesion, 0.0, "Cohesion c of intact contacts [Pa]")                                                                                           \
	X(Real, frictionAngle, 0.5, "Friction angle phi of intact contacts [rad]")                                                                            \
	X(Real, residualFrictionAngle, 0.5, "Friction angle of broken (cohesionless Coulomb) contacts [rad]")                                              \
	X(long, breakEvents, 0, "Contacts of this kind broken so far [-]") \
	X(long, stepSerial, 0, "Physical step counter; a contact sets itself up for a step when its own differs (internal) [-]") \
	X(bool, breaksAtEquilibrium, false, "Set by AdrLogTimeIntegrator: intact contacts break only when it has reached equilibrium, never in the "  \
	                                    "transients of its fictitious dynamics; false under other integrators: the law breaks at once [-]") \
	X(Real, shortestLag, 1e-2, "Shortest load duration the Kelvin chain resolves (set by AdrLogTimeIntegrator: first step) [day]") \
	X(Real, longestLag, 1e5, "Longest load duration the Kelvin chain resolves (set by AdrLogTimeIntegrator: the run span) [day]")
	SWELLDEM_CLASS(ContactKind, Serializable,
	               "Parameters shared by all contacts of one kind (MORTAR, ITZ or AGG): stiffness, aging viscoelasticity (B3), "
	               "swelling kinetics (Larive) and brittle strength.",
	               SWELLDEM_CONTACT_KIND_ATTRS)
	ContactKind() { }
	virtual ~ContactKind() { }
	void postLoad();
	template <class C> static void pyMethods(C& cls)
	{
		cls.def("compliance", &ContactKind::compliance, "B3 J(t, t') of the kind's q's, t and t' in days [1/Pa].");
		cls.def("modulus", &ContactKind::modulus, "Modulus of the kind at age t [day]: young, or E(t) = 1/J(t + 0.01, t) for aging kinds [Pa].");
		cls.def("chainSize", &ContactKind::chainSize, "Number of Kelvin units per direction of the prepared law (0 unless viscoelastic) [-].");
		cls.def("evaluateHistory", &ContactKind::evaluateHistory,
		        (boost::python::arg("times"), boost::python::arg("openings"), boost::python::arg("area"), boost::python::arg("length"),
		         boost::python::arg("swellDispInf") = -1.0),
		        "One contact of this kind alone, outside any scene: the physics core driven through physical times [day] "
		        "with imposed normal openings [m] (one per time, times[0] the stress-free state), facet area [m2] and length [m]; "
		        "returns the normal force [N] at each time (tension positive).");
	}

	// --- runtime, not serialized
	swelldem::core::ContactKindParams params() const;
	/// params(), validated; the error names this kind.
	swelldem::core::ContactKindParams checkedParams() const;
	/// Builds the core law for an analysis with these lags [day] (AdrLogTimeIntegrator calls it).
	void prepare(Real shortestLag, Real longestLag);
	/// The core law; built with default lags on first use if the integrator has not prepared it.
	swelldem::core::ContactLaw& law();
	Real compliance(Real t, Real tPrime) const;
	Real modulus(Real t) const;
	int  chainSize();
	std::vector<Real> evaluateHistory(const std::vector<Real>& times, const std::vector<Real>& openings, Real area, Real length, Real swellDispInf) const;

private:
	std::unique_ptr<swelldem::core::ContactLaw>  law_;
	std::atomic<swelldem::core::ContactLaw*>     lawReady_ { nullptr }; // lock-free read once built
	std::mutex                                   lawMutex_;
};

} // namespace yade
