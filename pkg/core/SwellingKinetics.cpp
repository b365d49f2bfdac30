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
    for (int i = 0; i < ns; ++i) {
        const double tm = t0 + (i + 0.5) * h;
        const double Tm = T(tm);
        const double tc = tauC(Tm);  // validates Tm
        const double c = std::exp(-tauL(Tm) / tc);
        const double E = std::exp(-h / tc);
        const double oneMinusE = -std::expm1(-h / tc);
        // exact solution over h: xi' = (xi (1 + c E) + c (1 - E)) / ((1 - xi) E + xi + c)
        x = (x * (1.0 + c * E) + c * oneMinusE) / ((1.0 - x) * E + x + c);
        x = std::min(x, 1.0);
    }
    return x;
}

double SwellingKinetics::integrate(double xi0, double t0, double t1, const std::vector<double>& times,
                                   const std::vector<double>& temperatures, int substeps) const
{
    require(!times.empty() && times.size() == temperatures.size(), "temperature table size",
            static_cast<double>(times.size()),
            "same non-zero length as the temperatures (" + std::to_string(temperatures.size()) + ")");
    for (std::size_t i = 0; i < times.size(); ++i) {
        requirePositive("temperature[" + std::to_string(i) + "] [K]", temperatures[i]);
        if (i > 0)
            requireGreater("time[" + std::to_string(i) + "] [day]", times[i],
                           "time[" + std::to_string(i - 1) + "]", times[i - 1]);
    }
    auto T = [&](double t) {
        if (t <= times.front()) return temperatures.front();
        if (t >= times.back()) return temperatures.back();
        const auto it = std::upper_bound(times.begin(), times.end(), t);
        const std::size_t j = static_cast<std::size_t>(it - times.begin());
        const double a = (t - times[j - 1]) / (times[j] - times[j - 1]);
        return temperatures[j - 1] + a * (temperatures[j] - temperatures[j - 1]);
    };
    return integrate(xi0, t0, t1, T, substeps);
}

}  // namespace swelldem::core
