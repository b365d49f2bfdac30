// SPDX-License-Identifier: GPL-2.0-or-later
// Parameters shared by all contacts of one kind (MORTAR, ITZ, AGG, ...): one set per kind, kept
// apart from the per-contact state (ContactState) and geometry (ContactGeometry).
//
// SWELLDEM_KIND_PARAMETERS is the one table of the per-kind parameters a user sets: name as the
// user sees it (YADE's ContactKind attribute, the scenarios' per-kind options), the member of this
// struct it sets, its default and its documentation with unit. The YADE adapter generates its
// Python attributes and its serialization from it; validate() below is the one place that checks
// their ranges. A new per-kind parameter is one line here and its check in ContactKindParams.cpp.
#pragma once

#include "core/B3Compliance.hpp"
#include "core/BrittleContact.hpp"
#include "core/KelvinChain.hpp"
#include "core/SolidificationCreep.hpp"
#include "core/SwellingKinetics.hpp"
#include "core/TemperatureHistory.hpp"

#include <string>
#include <vector>

// X(type, name, member, default, "doc [unit]"); a default the core struct already holds is named from
// there (KelvinChainOptions, B3Params), so that each has one home.
#define SWELLDEM_KIND_PARAMETERS(X)                                                                                        \
    X(double, young, contactModulus, 30e9, "Contact modulus E_c of 'elastic' kinds; kn = E_c A / L [Pa]")                  \
    X(double, shearRatio, shearRatio, 0.3, "alpha = ks / kn [-]")                                                          \
    X(double, q1, b3.q1, 6.7e-12, "B3 instantaneous compliance q1 [1/Pa] (paper Table 3.3: 1e-6/MPa = 1e-12/Pa)")          \
    X(double, q2, b3.q2, 108.1e-12, "B3 aging viscoelastic compliance q2 [1/Pa]")                                          \
    X(double, q3, b3.q3, 44.2e-12, "B3 non-aging viscoelastic compliance q3 [1/Pa]")                                       \
    X(double, q4, b3.q4, 14.3e-12, "B3 flow compliance q4 [1/Pa]")                                                         \
    X(double, elasticLag, b3.elasticLag, B3Params().elasticLag,                                                                          \
      "Load duration of the static modulus E(t) = 1/J(t + elasticLag, t) of 'aging-elastic' kinds [day]")                 \
    X(double, kelvinUnitsPerDecade, chain.unitsPerDecade, KelvinChainOptions().unitsPerDecade,                                                          \
      "Kelvin units per decade of retardation time (cost against accuracy) [1/decade]")                                    \
    X(double, kelvinMarginAbove, chain.marginAbove, KelvinChainOptions().marginAbove,                                                                \
      "Decades of retardation times beyond the run's longest load duration t_end - t_start: the chain's slowest unit "     \
      "is >= that duration x 10^margin, so creep late in the run is not cut off by a missing unit (0..6) [decade]")      \
    X(bool, swelling, swelling, false, "Evaluate swelling kinetics for this kind (set when any of its contacts swells) [-]") \
    X(double, swellDispInf, swellingDisplacementInf, 0.0,                                                                 \
      "Ultimate free swelling displacement d_inf of the kind's contacts (0: none; per-contact override "                  \
      "SwellPhys.swellDispInf) [m]")                                                                                       \
    X(double, tauC, tauC, 50.0, "Larive characteristic time tau_c at the reference temperature [day]")                    \
    X(double, tauL, tauL, 100.0, "Larive latency time tau_L at the reference temperature [day]")                          \
    X(double, referenceTemperature, referenceTemperature, SwellingKinetics::kT0,                                          \
      "Reference temperature T0 of the swelling kinetics: tauC and tauL are their values at T0 [K]")                     \
    X(double, Uc, Uc, SwellingKinetics::kUc,                                                                              \
      "Activation energy / R of tau_c: tau_c(T) = tau_c(T0) exp[Uc (1/T - 1/T0)] (Ulm et al. 2000: 5400 +- 500 K) [K]") \
    X(double, UL, UL, SwellingKinetics::kUL,                                                                              \
      "Activation energy / R of tau_L: tau_L(T) = tau_L(T0) exp[UL (1/T - 1/T0)] (Ulm et al. 2000: 9400 +- 500 K) [K]") \
    X(std::vector<double>, temperatureDays, temperatureDays, std::vector<double>(),                                       \
      "Days of the kind's temperature history, >= 0 and strictly increasing, T linear in between and held before the "  \
      "first and after the last; empty: no history, the swelling kinetics at referenceTemperature and creep at "          \
      "creepReferenceTemperature; ContactKind.setTemperatureHistory sets both lists at once [day]")                      \
    X(std::vector<double>, temperatures, temperatures, std::vector<double>(),                                             \
      "Temperatures of the history, one per day of temperatureDays, 0 < T <= 373.15 [K]")                                \
    X(bool, thermalCreep, thermal.on, ThermalCreepParams().on,                                                            \
      "Creep of aging kinds follows the temperature history (microprestress-solidification theory's temperature form: "  \
      "equivalent age, reduced time, flow viscosity; docs/temperature.md); False: only the swelling kinetics see it [-]") \
    X(double, creepReferenceTemperature, thermal.T0, ThermalCreepParams().T0,                                             \
      "Temperature at which the B3 q's hold (creep runs at its nominal rate) [K]")                                       \
    X(double, creepUe, thermal.Ue, ThermalCreepParams().Ue,                                                               \
      "Activation energy / R of hydration: the solidified volume ages in the equivalent age t_e, dt_e/dt = "             \
      "exp[creepUe (1/T0 - 1/T)] [K]")                                                                                   \
    X(double, creepUr, thermal.Ur, ThermalCreepParams().Ur,                                                               \
      "Activation energy / R of the viscous processes: the Kelvin units and the flow run in the reduced time t_r [K]")   \
    X(double, creepUs, thermal.Us, ThermalCreepParams().Us,                                                               \
      "Activation energy / R of microprestress relaxation: the flow viscosity grows as t_s/q4, t_s its clock [K]")       \
    X(bool, damage, strength.damage, false, "Brittle failure on: tension cut-off f_t A, optional Mohr-Coulomb shear failure [-]") \
    X(double, tensileStrength, strength.tensileStrength, 4e6, "f_t; a contact breaks when Fn > f_t A [Pa]")               \
    X(bool, shearFailure, strength.shearFailure, false,                                                                   \
      "Mohr-Coulomb shear failure of intact contacts, |Fs| > c A + tan(phi) max(-Fn, 0) (the paper keeps it off) [-]")    \
    X(double, cohesion, strength.cohesion, 0.0, "Cohesion c of intact contacts [Pa]")                                     \
    X(double, frictionAngle, strength.frictionAngle, 0.5, "Friction angle phi of intact contacts [rad]")                  \
    X(double, residualFrictionAngle, strength.residualFrictionAngle, 0.5,                                                 \
      "Friction angle of broken (cohesionless Coulomb) contacts [rad]")

namespace swelldem::core {

enum class Behaviour {
    Elastic,       ///< constant contact modulus E_c; no Kelvin state
    AgingElastic,  ///< dF = kn(t*) du with E(t) = 1/J(t + elasticLag, t) of the B3 params; no Kelvin state
    Viscoelastic   ///< solidification theory (B3) with a Kelvin chain per direction
};

/// The user's name of a behaviour ('elastic', 'aging-elastic', 'viscoelastic') and back; parse
/// throws std::invalid_argument naming the allowed names.
const char* behaviourName(Behaviour b);
Behaviour parseBehaviour(const std::string& name);

struct ContactKindParams {
    Behaviour behaviour = Behaviour::Elastic;
    double contactModulus;       ///< E_c [Pa] (Elastic kinds), > 0
    B3Params b3;                 ///< B3 parameters (AgingElastic, Viscoelastic)
    double shearRatio;           ///< alpha = ks/kn [-], > 0
    KelvinChainOptions chain;    ///< Kelvin chain construction (Viscoelastic)
    InteriorTime interiorTime = InteriorTime::Geometric;  ///< t* rule (aging kinds)

    bool swelling;                      ///< imposed swelling displacement on/off
    double swellingDisplacementInf;     ///< d_inf [m] (paper: eps_inf x 2 R_mean), >= 0
    double swellingStrainInf = 0;       ///< alternative: d_inf = eps_inf x L per contact [-], >= 0
    double tauC;                        ///< characteristic time at T0 [day]
    double tauL;                        ///< latency time at T0 [day]
    double referenceTemperature;        ///< T0 of the kinetics [K]
    double Uc;                          ///< [K]
    double UL;                          ///< [K]
    std::vector<double> temperatureDays;  ///< temperature history: days [day] (empty: none)
    std::vector<double> temperatures;     ///< and temperatures [K]
    ThermalCreepParams thermal;           ///< creep at temperature (aging kinds with a history)

    BrittleStrength strength;           ///< damage (off by default)

    /// Every member of the table at its default.
    ContactKindParams();
    /// Throws std::invalid_argument naming the first parameter out of range; only the
    /// parameters the behaviour uses are checked.
    void validate() const;
    /// Same values (parameters compared exactly; used to see whether a live kind was changed).
    bool operator==(const ContactKindParams& o) const;
    bool operator!=(const ContactKindParams& o) const { return !(*this == o); }
};

}  // namespace swelldem::core
