// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/SolidificationCreep.hpp"

#include "core/Validate.hpp"

#include <cmath>

namespace swelldem::core {

namespace {

const B3Params& validated(const B3Params& p)
{
    p.validate();
    return p;
}

// 1 - lambda with lambda = (1 - exp(-x))/x, x = dt/tau >= 0, without cancellation for small x.
double oneMinusLambda(double x, double oneMinusBeta)
{
    if (x < 1e-3) return x * (0.5 - x * (1.0 / 6 - x * (1.0 / 24 - x * (1.0 / 120 - x / 720))));
    return (x - oneMinusBeta) / x;
}

// w = 1 - ln(1+x)/x, x = dt/tPrev >= 0.
double flowShare(double x, double lnRatio)
{
    if (x < 1e-4) return x * (0.5 - x * (1.0 / 3 - x * (0.25 - x / 5)));
    return 1.0 - lnRatio / x;
}

}  // namespace

SolidificationCreep::SolidificationCreep(const B3Params& p, double shortestLag, double longestLag,
                                         const KelvinChainOptions& opt, InteriorTime rule)
    : p_(validated(p)),
      chain_(KelvinChain::forAnalysis(p.q2, p.n, p.lambda0, shortestLag, longestLag, opt)),
      rule_(rule)
{
}

SolidificationCreep::SolidificationCreep(const B3Params& p, std::vector<double> tau,
                                         const KelvinChainOptions& opt, InteriorTime rule)
    : p_(validated(p)), chain_(p.q2, p.n, p.lambda0, std::move(tau), opt), rule_(rule)
{
}

double SolidificationCreep::interiorTime(InteriorTime rule, double tPrev, double t)
{
    if (t == tPrev) return t;
    return rule == InteriorTime::Geometric ? std::sqrt(tPrev) * std::sqrt(t) : 0.5 * (tPrev + t);
}

StepFactors SolidificationCreep::factors(double tPrev, double t) const
{
    StepFactors f;
    factors(tPrev, t, f);
    return f;
}

void SolidificationCreep::factors(double tPrev, double t, StepFactors& f) const
{
    requirePositive("tPrev [day]", tPrev);
    requireGreaterEqual("t [day]", t, "tPrev", tPrev);
    const std::size_t N = chain_.size();
    f.tPrev = tPrev;
    f.t = t;
    f.dt = t - tPrev;
    f.tStar = interiorTime(rule_, tPrev, t);
    f.invV = std::pow(p_.lambda0 / f.tStar, p_.m) + p_.q3 / p_.q2;
    const double x = f.dt / tPrev;
    f.flowLog = std::log1p(x);
    f.flowW = flowShare(x, f.flowLog);
    f.q4 = p_.q4;
    f.oneMinusBeta.resize(N);
    f.A1mB.resize(N);
    f.A1mL.resize(N);
    const auto& tau = chain_.tau();
    const auto& A = chain_.A();
    double sumL = chain_.A0();
    f.sumA1mB = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const double xi = f.dt / tau[i];
        const double omb = -std::expm1(-xi);  // 1 - beta, exact for tiny xi, 1 for huge xi
        f.oneMinusBeta[i] = omb;
        f.A1mB[i] = A[i] * omb;
        f.A1mL[i] = A[i] * oneMinusLambda(xi, omb);
        f.sumA1mB += f.A1mB[i];
        sumL += f.A1mL[i];
    }
    f.invEpp = p_.q1 + f.invV * sumL + p_.q4 * f.flowW;
}

double SolidificationCreep::inelasticStrainIncrement(const StepFactors& f, double sigmaPrev,
                                                     const double* gamma)
{
    double s = sigmaPrev * f.sumA1mB;
    for (std::size_t i = 0; i < f.oneMinusBeta.size(); ++i) s -= f.oneMinusBeta[i] * gamma[i];
    return f.invV * s + f.q4 * sigmaPrev * f.flowLog;
}

void SolidificationCreep::commit(const StepFactors& f, double sigmaPrev, double dsigma, double* gamma)
{
    for (std::size_t i = 0; i < f.oneMinusBeta.size(); ++i)
        gamma[i] += f.A1mB[i] * sigmaPrev - f.oneMinusBeta[i] * gamma[i] + f.A1mL[i] * dsigma;
}

}  // namespace swelldem::core
