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
#pragma once

#include "core/B3Compliance.hpp"
#include "core/KelvinChain.hpp"

#include <cstddef>
#include <vector>

namespace swelldem::core {

/// Interior time t* of a step at which 1/v is evaluated.
enum class InteriorTime {
    Geometric,  ///< t* = sqrt(tPrev t) (mid-point in log time; the default)
    Arithmetic  ///< t* = (tPrev + t)/2
};

/// Factors of one physical step shared by all contacts of one material.
struct StepFactors {
    double tPrev = 0;     ///< step start [day]
    double t = 0;         ///< step end [day]
    double dt = 0;        ///< t - tPrev [day]
    double tStar = 0;     ///< interior time [day]
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
