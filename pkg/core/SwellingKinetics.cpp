// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/SwellingKinetics.hpp"

#include "core/Validate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace swelldem::core {

SwellingKinetics::SwellingKinetics(double tauC, double tauL, double T0, double Uc, double UL)
    : tauC_(tauC), tauL_(tauL), T0_(T0), Uc_(Uc), UL_(UL)
{
    requirePositive("tau_c [day]", tauC);
    require(tauL >= 0 && tauL <= kMaxLatencyRatio * tauC, "tau_L [day]", tauL,
            "0 <= tau_L <= 700 tau_c = " + formatNumber(kMaxLatencyRatio * tauC));
    requirePositive("T0 [K]", T0);
    requireNonNegative("U_c [K]", Uc);
    requireNonNegative("U_L [K]", UL);
}

double SwellingKinetics::tauC(double T) const
{
    requirePositive("T [K]", T);
    return tauC_ * std::exp(Uc_ * (1.0 / T - 1.0 / T0_));
}

double SwellingKinetics::tauL(double T) const
{
    requirePositive("T [K]", T);
    return tauL_ * std::exp(UL_ * (1.0 / T - 1.0 / T0_));
}

double SwellingKinetics::logistic(double z)
{
    if (z >= 0) return 1.0 / (1.0 + std::exp(-z));
    const double e = std::exp(z);
    return e / (1.0 + e);
}

// xi = N(t) S(t), N = 1 - e^(-t/tc), S = logistic((t - tl)/tc): no overflow for any t >= 0.
double SwellingKinetics::xiClosed(double t, double tc, double tl) const
{
    return -std::expm1(-t / tc) * logistic((t - tl) / tc);
}

// xi2 - xi1 = (N2 - N1) S2 + N1 (S2 - S1) with
//   N2 - N1 = e^(-t1/tc) (1 - e^(-dt/tc)),  S2 - S1 = (1 - e^(-dt/tc)) S2 (1 - S1):
// every term is a product of non-negative factors, so tiny steps keep full relative precision.
double SwellingKinetics::incrementClosed(double t1, double t2, double tc, double tl) const
{
    const double d = -std::expm1(-(t2 - t1) / tc);
    const double N1 = -std::expm1(-t1 / tc);
    const double S2 = logistic((t2 - tl) / tc);
    const double oneMinusS1 = logistic(-(t1 - tl) / tc);
    return std::exp(-t1 / tc) * d * S2 + N1 * d * S2 * oneMinusS1;
}

double SwellingKinetics::xi(double t) const
{
    requireNonNegative("t [day]", t);
    return xiClosed(t, tauC_, tauL_);
}

double SwellingKinetics::xiAt(double t, double T) const
{
    requireNonNegative("t [day]", t);
    return xiClosed(t, tauC(T), tauL(T));
}

double SwellingKinetics::increment(double t1, double t2) const
{
    requireNonNegative("t1 [day]", t1);
    requireGreaterEqual("t2 [day]", t2, "t1", t1);
    return incrementClosed(t1, t2, tauC_, tauL_);
}

double SwellingKinetics::incrementAt(double t1, double t2, double T) const
{
    requireNonNegative("t1 [day]", t1);
    requireGreaterEqual("t2 [day]", t2, "t1", t1);
    return incrementClosed(t1, t2, tauC(T), tauL(T));
}

double SwellingKinetics::rate(double xi, double T) const
{
    require(xi >= 0 && xi <= 1, "xi", xi, "0 <= xi <= 1");
    const double tc = tauC(T);
    const double c = std::exp(-tauL(T) / tc);
    return (1.0 - xi) * (xi + c) / (tc * (1.0 + c));
}

double SwellingKinetics::advance(double xi, double h, double T) const
{
    const double tc = tauC(T);  // validates T
    const double c = std::exp(-tauL(T) / tc);
    const double E = std::exp(-h / tc);
    const double oneMinusE = -std::expm1(-h / tc);
    // (xi' + c)/(1 - xi') = e^(h/tc) (xi + c)/(1 - xi), solved for xi'
    return std::min((xi * (1.0 + c * E) + c * oneMinusE) / ((1.0 - xi) * E + xi + c), 1.0);
}

double SwellingKinetics::integrate(double xi0, double t0, double t1, const std::function<double(double)>& T,
                                   int substeps) const
{
    require(xi0 >= 0 && xi0 <= 1, "xi0", xi0, "0 <= xi0 <= 1");
    requireNonNegative("t0 [day]", t0);
    requireGreaterEqual("t1 [day]", t1, "t0", t0);
    if (t1 == t0) return xi0;
    int ns = substeps;
    if (ns <= 0) {
        const double want = std::ceil(20.0 * (t1 - t0) / tauC_);
        ns = static_cast<int>(std::clamp(want, 1.0, 1e6));
    }
    const double h = (t1 - t0) / ns;
    double x = xi0;
    for (int i = 0; i < ns; ++i) x = advance(x, h, T(t0 + (i + 0.5) * h));
    return x;
}

double SwellingKinetics::integrate(double xi0, double t0, double t1, const std::vector<double>& times,
                                   const std::vector<double>& temperatures, int substeps) const
{
    require(!times.empty(), "len(temperatureDays)", 0.0, ">= 1 (a history)");
    const TemperatureHistory h(times, temperatures);
    return integrate(xi0, t0, t1, [&](double t) { return h.at(t); }, substeps);
}

SwellingHistory::SwellingHistory(const SwellingKinetics& kinetics, const TemperatureHistory& history)
    : k_(kinetics), h_(history)
{
    require(!h_.empty(), "len(temperatureDays)", 0.0, ">= 1 (a history)");
    if (h_.isConstant()) return;
    const auto& d = h_.days();
    const auto& T = h_.temperatures();
    nodes_.push_back(0.0);
    if (d.front() > 0) nodes_.push_back(d.front());
    for (std::size_t j = 0; j + 1 < d.size(); ++j) {
        const int n = std::max(1, static_cast<int>(std::ceil(std::fabs(T[j + 1] - T[j]) / kSubstepKelvin)));
        for (int i = 1; i < n; ++i) nodes_.push_back(d[j] + (d[j + 1] - d[j]) * i / n);
        nodes_.push_back(d[j + 1]);
    }
}

double SwellingHistory::xi(double t)
{
    requireNonNegative("t [day]", t);
    if (h_.isConstant()) return k_.xiAt(t, h_.temperatures().front());
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(nodes_.begin(), nodes_.end(), t) - nodes_.begin()) - 1;
    if (k < node_) {
        node_ = 0;
        xiNode_ = 0;
    }
    for (; node_ < k; ++node_) {
        const double a = nodes_[node_], b = nodes_[node_ + 1];
        xiNode_ = k_.advance(xiNode_, b - a, h_.at(0.5 * (a + b)));
    }
    const double a = nodes_[k];
    return t > a ? k_.advance(xiNode_, t - a, h_.at(0.5 * (a + t))) : xiNode_;
}

double SwellingHistory::increment(double t1, double t2)
{
    requireNonNegative("t1 [day]", t1);
    requireGreaterEqual("t2 [day]", t2, "t1", t1);
    if (h_.isConstant()) return k_.incrementAt(t1, t2, h_.temperatures().front());
    const double x1 = xi(t1);
    return xi(t2) - x1;
}

}  // namespace swelldem::core
