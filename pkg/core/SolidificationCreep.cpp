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

const TemperatureHistory& checked(const ThermalCreepParams& p, const TemperatureHistory& h)
{
    p.validate();
    return h;
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
    factors(StepTimes::identity(tPrev, t), f);
}

void SolidificationCreep::factors(const StepTimes& s, StepFactors& f) const
{
    requirePositive("tPrev [day]", s.tPrev);
    requireGreaterEqual("t [day]", s.t, "tPrev", s.tPrev);
    const std::size_t N = chain_.size();
    f.tPrev = s.tPrev;
    f.t = s.t;
    f.dt = s.t - s.tPrev;
    f.tStar = interiorTime(rule_, s.agePrev, s.age);
    f.invV = std::pow(p_.lambda0 / f.tStar, p_.m) + p_.q3 / p_.q2;
    const double x = (s.flow - s.flowPrev) / s.flowPrev;
    const double lnRatio = std::log1p(x);
    f.flowLog = s.flowRatio * lnRatio;
    f.flowW = s.flowRatio * flowShare(x, lnRatio);
    f.q4 = p_.q4;
    f.oneMinusBeta.resize(N);
    f.A1mB.resize(N);
    f.A1mL.resize(N);
    const auto& tau = chain_.tau();
    const auto& A = chain_.A();
    double sumL = chain_.A0();
    f.sumA1mB = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const double xi = s.reducedDt / tau[i];
        const double omb = -std::expm1(-xi);  // 1 - beta, exact for tiny xi, 1 for huge xi
        f.oneMinusBeta[i] = omb;
        f.A1mB[i] = A[i] * omb;
        f.A1mL[i] = A[i] * oneMinusLambda(xi, omb);
        f.sumA1mB += f.A1mB[i];
        sumL += f.A1mL[i];
    }
    f.invEpp = p_.q1 + f.invV * sumL + p_.q4 * f.flowW;
}

void ThermalCreepParams::validate() const
{
    require(T0 > 0 && T0 <= TemperatureHistory::kMaxTemperature, "creepReferenceTemperature [K]", T0,
            "0 < creepReferenceTemperature <= " + formatNumber(TemperatureHistory::kMaxTemperature) + " [K]");
    requireNonNegative("creepUe [K]", Ue);
    requireNonNegative("creepUr [K]", Ur);
    requireNonNegative("creepUs [K]", Us);
}

ThermalCreepClocks::ThermalCreepClocks(const ThermalCreepParams& p, const TemperatureHistory& history)
    : age_(checked(p, history), p.Ue, p.T0), reduced_(history, p.Ur, p.T0), flow_(history, p.Us, p.T0), h_(history)
{
}

StepTimes ThermalCreepClocks::step(double tPrev, double t) const
{
    requirePositive("tPrev [day]", tPrev);
    requireGreaterEqual("t [day]", t, "tPrev", tPrev);
    StepTimes s;
    s.tPrev = tPrev;
    s.t = t;
    s.agePrev = age_.at(tPrev);
    s.age = age_.at(t);
    s.reducedDt = reduced_.integral(tPrev, t);
    s.flowPrev = flow_.at(tPrev);
    s.flow = flow_.at(t);
    const double dFlow = flow_.integral(tPrev, t);
    if (dFlow > 0) {
        s.flowRatio = s.reducedDt / dFlow;
    } else if (!h_.empty()) {  // an instantaneous step has no flow; its ratio is the rates' at t
        const double T = h_.at(t);
        s.flowRatio = reduced_.factor(T) / flow_.factor(T);
    }
    return s;
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
