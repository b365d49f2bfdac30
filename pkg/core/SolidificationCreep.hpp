// SPDX-License-Identifier: GPL-2.0-or-later
// Solidification theory (Bazant & Prasannan 1989) for one contact direction, integrated over a
// physical step [tPrev, t] with the exponential algorithm:
//   stress-strain:  d(eps)/dt = q1 d(sigma)/dt + (1/v(t)) d(gamma)/dt + q4 sigma / t,
//   micro-strain:   gamma = A0 sigma + sum_mu gamma_mu,  tau_mu d(gamma_mu)/dt + gamma_mu = A_mu sigma.
// Over one step with sigma linear in time:
//   dsigma = E'' (deps - deps''),
//   1/E''   = q1 + (1/v(t*)) [A0 + sum_mu (1 - lambda_mu) A_mu] + q4 w,
//   deps''  = (1/v(t*)) sum_mu (1 - beta_mu)(A_mu sigma_prev - gamma_mu) + q4 sigma_prev ln(t/tPrev),
//   beta = exp(-dt/tau), lambda = (1 - beta) tau/dt, w = 1 - (tPrev/dt) ln(t/tPrev).
// The flow term is integrated exactly for linear sigma (paper: q4 F(t*) dt/t*).
// Shared, per-step factors (StepFactors) are computed once per material and step; the per-contact
// work is inelasticStrainIncrement() and commit() on the contact's hidden array gamma[size()].
// Units: days, Pa, 1/Pa; strains dimensionless.
//
// Creep at temperature (ThermalCreepParams, ThermalCreepClocks): the temperature form of the
// microprestress-solidification (MPS) theory (Bazant, Cedolin & Cusatis, J. Eng. Mech. 130(6),
// 2004; as reformulated by Jirasek & Havlasek, Cem. Concr. Res. 60, 2014), without its transient
// thermal creep term. Three Arrhenius clocks, dt_x/dt = exp[U_x (1/T0 - 1/T)]:
//   t_e (U_e, hydration):  the solidified volume ages in t_e,            1/v(t_e);
//   t_r (U_r, viscous):    the Kelvin units run in t_r,                  tau_mu dgamma_mu/dt_r + gamma_mu = A_mu sigma;
//   t_s (U_s, microprestress relaxation): the flow viscosity eta = t_s/q4, and the flow runs in t_r:
//                          deps_f/dt = psi_r sigma / eta = q4 sigma psi_r / t_s.
// At a constant T from t = 0 (t_x = psi_x t) this is the reference-temperature law in transformed
// variables: J_T(t, t') = q1 + rho^(-m) q2 Q(psi_r t, psi_r t') + q3 ln(1 + (psi_r (t - t')/lambda0)^n)
//   + q4 (psi_r/psi_s) ln(t/t'), rho = psi_e/psi_r.
// Over a step, StepTimes carries the clocks at its ends: t* from t_e, beta_mu and lambda_mu from
// the increment of t_r, and the flow term from t_s times the step's psi_r/psi_s (Delta t_r / Delta
// t_s): exact at a constant temperature, stress taken linear in t_s under a varying one.
#pragma once

#include "core/B3Compliance.hpp"
#include "core/KelvinChain.hpp"
#include "core/TemperatureHistory.hpp"

#include <cstddef>
#include <vector>

namespace swelldem::core {

/// Interior time t* of a step at which 1/v is evaluated.
enum class InteriorTime {
    Geometric,  ///< t* = sqrt(tPrev t) (mid-point in log time; the default)
    Arithmetic  ///< t* = (tPrev + t)/2
};

/// Creep at temperature (see the top of this file); defaults: the activation energies of the MPS
/// theory as OOFEM's material library documents them (Q_e/R = 2700 K, Q_r/R = 5000 K,
/// Q_s/R = 3000 K), the B3 q's taken at 20 C.
struct ThermalCreepParams {
    bool on = true;          ///< creep sees the temperature history (false: only the swelling kinetics do)
    double T0 = 293.15;      ///< temperature at which the B3 q's hold [K], 0 < T0 <= 373.15
    double Ue = 2700.0;      ///< activation energy / R of hydration (equivalent age) [K], >= 0
    double Ur = 5000.0;      ///< of the viscous processes (Kelvin units, flow rate) [K], >= 0
    double Us = 3000.0;      ///< of microprestress relaxation (flow viscosity) [K], >= 0
    /// Throws std::invalid_argument naming the first value out of range.
    void validate() const;
};

/// The times of one physical step [tPrev, t] as the creep law sees them [day]; identity() is the
/// reference temperature (all clocks the physical time).
struct StepTimes {
    double tPrev = 0, t = 0;        ///< physical step ends
    double agePrev = 0, age = 0;    ///< equivalent age t_e at both ends (1/v, t*)
    double reducedDt = 0;           ///< increment of t_r (the Kelvin units' time)
    double flowPrev = 0, flow = 0;  ///< t_s at both ends (the flow's logarithm)
    double flowRatio = 1;           ///< psi_r/psi_s over the step, Delta t_r / Delta t_s [-]
    static StepTimes identity(double tPrev, double t)
    {
        return StepTimes{tPrev, t, tPrev, t, t - tPrev, tPrev, t, 1.0};
    }
};

/// The three MPS clocks of a kind under a temperature history.
class ThermalCreepClocks {
public:
    ThermalCreepClocks(const ThermalCreepParams& p, const TemperatureHistory& history);
    /// StepTimes of [tPrev, t]; 0 < tPrev <= t [day]. A function of (tPrev, t) alone.
    StepTimes step(double tPrev, double t) const;
    const ArrheniusTime& equivalentAge() const { return age_; }
    const ArrheniusTime& reducedTime() const { return reduced_; }
    const ArrheniusTime& flowTime() const { return flow_; }

private:
    ArrheniusTime age_, reduced_, flow_;
    TemperatureHistory h_;
};

/// Factors of one physical step shared by all contacts of one material.
struct StepFactors {
    double tPrev = 0;     ///< step start [day]
    double t = 0;         ///< step end [day]
    double dt = 0;        ///< t - tPrev [day]
    double tStar = 0;     ///< interior time (of the equivalent age at temperature) [day]
    double invV = 0;      ///< 1/v(t*) [-]
    double flowLog = 0;   ///< ln(t/tPrev) [-]
    double flowW = 0;     ///< w = 1 - (tPrev/dt) ln(t/tPrev) [-], share of dsigma in the flow
    double q4 = 0;        ///< flow compliance [1/Pa]
    double invEpp = 0;    ///< incremental compliance 1/E'' [1/Pa]
    double sumA1mB = 0;   ///< sum_mu A_mu (1 - beta_mu) [1/Pa]
    std::vector<double> oneMinusBeta;  ///< 1 - beta_mu [-]
    std::vector<double> A1mB;          ///< A_mu (1 - beta_mu) [1/Pa]
    std::vector<double> A1mL;          ///< A_mu (1 - lambda_mu) [1/Pa]

    double Epp() const { return 1.0 / invEpp; }  ///< incremental modulus E'' [Pa]
    std::size_t size() const { return oneMinusBeta.size(); }
};

class SolidificationCreep {
public:
    /// Chain range from the analysis (see KelvinChain::forAnalysis) [day].
    SolidificationCreep(const B3Params& p, double shortestLag, double longestLag,
                        const KelvinChainOptions& opt = {}, InteriorTime rule = InteriorTime::Geometric);
    /// Chain with explicit retardation times [day].
    SolidificationCreep(const B3Params& p, std::vector<double> tau, const KelvinChainOptions& opt = {},
                        InteriorTime rule = InteriorTime::Geometric);

    const B3Params& params() const { return p_; }
    const KelvinChain& chain() const { return chain_; }
    InteriorTime interiorTimeRule() const { return rule_; }
    /// Hidden doubles per contact direction (the Kelvin strains gamma_mu).
    std::size_t size() const { return chain_.size(); }

    /// Shared step factors for [tPrev, t]; requires t >= tPrev > 0 [day]. dt = 0 is an
    /// instantaneous step (only q1 + A0/v(t) responds).
    StepFactors factors(double tPrev, double t) const;
    /// Same, into an existing object (reuses its vectors, no allocation after the first call).
    void factors(double tPrev, double t, StepFactors& out) const;
    /// Same under temperature (ThermalCreepClocks::step); StepTimes::identity(tPrev, t) gives
    /// factors(tPrev, t) bit for bit.
    void factors(const StepTimes& s, StepFactors& out) const;

    /// Inelastic strain increment deps'' of the step, constant during its iterations [-].
    /// sigmaPrev: committed stress [Pa]; gamma: the contact's hidden array [f.size()].
    static double inelasticStrainIncrement(const StepFactors& f, double sigmaPrev, const double* gamma);
    /// Stress increment for a total strain increment: E'' (deps - deps'') [Pa].
    static double stressIncrement(const StepFactors& f, double deps, double depsInelastic)
    {
        return (deps - depsInelastic) / f.invEpp;
    }
    /// Updates the hidden strains once the step has converged (sigmaPrev, dsigma in Pa).
    static void commit(const StepFactors& f, double sigmaPrev, double dsigma, double* gamma);

    /// t* of [tPrev, t] by the given rule [day].
    static double interiorTime(InteriorTime rule, double tPrev, double t);

private:
    B3Params p_;
    KelvinChain chain_;
    InteriorTime rule_;
};

}  // namespace swelldem::core
