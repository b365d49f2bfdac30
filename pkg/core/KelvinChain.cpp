// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/KelvinChain.hpp"

#include "core/Validate.hpp"

#include <cmath>
#include <string>

namespace swelldem::core {

namespace {

constexpr int kMaxOrder = 8;

void validateCommon(double q2, double n, double lambda0, int order, bool richardson)
{
    requirePositive("q2 [1/Pa]", q2);
    requireOpenInterval("n", n, 0.0, 1.0);
    requirePositive("lambda0 [day]", lambda0);
    const int maxOrder = richardson ? kMaxOrder / 2 : kMaxOrder;
    require(order >= 1 && order <= maxOrder, "order (Post-Widder)", order,
            "integer 1 <= order <= " + std::to_string(maxOrder) +
                (richardson ? " (with Richardson extrapolation)" : ""));
}

// Signed Stirling numbers of the first kind s(k, j): x(x-1)...(x-k+1) = sum_j s(k,j) x^j.
std::vector<double> stirlingFirst(int k)
{
    std::vector<double> c(k + 1, 0.0);
    c[0] = 1.0;  // the empty product
    for (int i = 0; i < k; ++i) {  // multiply by (x - i)
        for (int j = i + 1; j >= 1; --j) c[j] = c[j - 1] - i * c[j];
        c[0] = -i * c[0];
    }
    return c;
}

// With w = ln u, u = (xi/lambda0)^n, F(w) = ln(1 + e^w) and s = u/(1+u) (logistic of w):
// d^j F / dw^j = P_j(s), P_1(s) = s, P_{j+1}(s) = s(1-s) P_j'(s). Returns P_0..P_k at s
// with P_0 = F = ln(1+u).
std::vector<double> logisticDerivatives(int k, double u)
{
    const double s = u / (1.0 + u);
    std::vector<double> out(k + 1, 0.0);
    out[0] = std::log1p(u);
    std::vector<double> coef{0.0, 1.0};  // P_1 = s (coefficients in powers of s)
    for (int j = 1; j <= k; ++j) {
        double v = 0, sp = 1;
        for (double c : coef) { v += c * sp; sp *= s; }
        out[j] = v;
        // next: s(1-s) * dP/ds
        std::vector<double> d(coef.size() > 1 ? coef.size() - 1 : 1, 0.0);
        for (std::size_t i = 1; i < coef.size(); ++i) d[i - 1] = i * coef[i];
        std::vector<double> nxt(d.size() + 2, 0.0);
        for (std::size_t i = 0; i < d.size(); ++i) {
            nxt[i + 1] += d[i];
            nxt[i + 2] -= d[i];
        }
        coef = nxt;
    }
    return out;
}

double factorial(int k)
{
    double f = 1;
    for (int i = 2; i <= k; ++i) f *= i;
    return f;
}

// xi^k Phi^(k)(xi) = sum_j s(k,j) D^j Phi with D = xi d/dxi = n d/dw, D^j Phi = q2 n^j P_j(s).
double postWidder(double tau, double q2, double n, double lambda0, int order)
{
    const int k = order;
    const double u = std::pow(k * tau / lambda0, n);
    const auto P = logisticDerivatives(k, u);
    const auto s = stirlingFirst(k);
    double sum = 0, nj = 1;
    for (int j = 1; j <= k; ++j) {
        nj *= n;
        sum += s[j] * nj * P[j];
    }
    const double sign = (k % 2 == 0) ? -1.0 : 1.0;  // -(-1)^k
    return sign / factorial(k - 1) * q2 * sum;
}

// integral of D^j Phi over ln tau = (1/n) integral over w = q2 n^(j-1) P_{j-1}(s), zero at -inf
double postWidderIntegralBelow(double tau, double q2, double n, double lambda0, int order)
{
    const int k = order;
    const double u = std::pow(k * tau / lambda0, n);
    const auto P = logisticDerivatives(k, u);
    const auto s = stirlingFirst(k);
    double sum = 0, nj1 = 1;
    for (int j = 1; j <= k; ++j) {
        sum += s[j] * nj1 * P[j - 1];
        nj1 *= n;
    }
    const double sign = (k % 2 == 0) ? -1.0 : 1.0;
    return sign / factorial(k - 1) * q2 * sum;
}

}  // namespace

void KelvinChainOptions::validate() const
{
    require(unitsPerDecade >= 0.1 && unitsPerDecade <= 20, "unitsPerDecade", unitsPerDecade,
            "0.1 <= unitsPerDecade <= 20");
    const int maxOrder = richardson ? kMaxOrder / 2 : kMaxOrder;
    require(order >= 1 && order <= maxOrder, "order (Post-Widder)", order,
            "integer 1 <= order <= " + std::to_string(maxOrder) +
                (richardson ? " (with Richardson extrapolation)" : ""));
    requireNonNegative("marginBelow [decades]", marginBelow);
    require(marginAbove >= 0 && marginAbove <= 6, "kelvinMarginAbove [decades]", marginAbove, "0 <= kelvinMarginAbove <= 6");
}

double KelvinChain::spectrum(double tau, double q2, double n, double lambda0, int order, bool richardson)
{
    validateCommon(q2, n, lambda0, order, richardson);
    requirePositive("tau [day]", tau);
    if (!richardson) return postWidder(tau, q2, n, lambda0, order);
    return 2.0 * postWidder(tau, q2, n, lambda0, 2 * order) - postWidder(tau, q2, n, lambda0, order);
}

double KelvinChain::spectrumIntegralBelow(double tau, double q2, double n, double lambda0, int order,
                                          bool richardson)
{
    validateCommon(q2, n, lambda0, order, richardson);
    requirePositive("tau [day]", tau);
    if (!richardson) return postWidderIntegralBelow(tau, q2, n, lambda0, order);
    return 2.0 * postWidderIntegralBelow(tau, q2, n, lambda0, 2 * order) -
           postWidderIntegralBelow(tau, q2, n, lambda0, order);
}

KelvinChain::KelvinChain(double q2, double n, double lambda0, std::vector<double> tau,
                         const KelvinChainOptions& opt)
    : q2_(q2), n_(n), lambda0_(lambda0), opt_(opt), tau_(std::move(tau))
{
    opt_.validate();
    validateCommon(q2, n, lambda0, opt_.order, opt_.richardson);
    require(!tau_.empty(), "number of retardation times", 0.0, ">= 1");
    for (std::size_t i = 0; i < tau_.size(); ++i) {
        const std::string name = "tau[" + std::to_string(i) + "] [day]";
        if (i == 0) requirePositive(name, tau_[i]);
        else requireGreater(name, tau_[i], "tau[" + std::to_string(i - 1) + "]", tau_[i - 1]);
    }
    const std::size_t N = tau_.size();
    std::vector<double> lnT(N);
    for (std::size_t i = 0; i < N; ++i) lnT[i] = std::log(tau_[i]);
    A_.resize(N);
    double lowerEdge = 0;  // ln tau at the lower edge of the first cell
    for (std::size_t i = 0; i < N; ++i) {
        double lo, hi;
        if (N == 1) {
            lo = lnT[0] - 0.5 * std::log(10.0);
            hi = lnT[0] + 0.5 * std::log(10.0);
        } else {
            lo = (i > 0) ? 0.5 * (lnT[i - 1] + lnT[i]) : lnT[0] - 0.5 * (lnT[1] - lnT[0]);
            hi = (i + 1 < N) ? 0.5 * (lnT[i] + lnT[i + 1]) : lnT[i] + 0.5 * (lnT[i] - lnT[i - 1]);
        }
        if (i == 0) lowerEdge = lo;
        A_[i] = spectrum(tau_[i], q2, n, lambda0, opt_.order, opt_.richardson) * (hi - lo);
    }
    A0_ = spectrumIntegralBelow(std::exp(lowerEdge), q2, n, lambda0, opt_.order, opt_.richardson);
}

KelvinChain KelvinChain::forRange(double q2, double n, double lambda0, double tauMin, double tauMax,
                                  const KelvinChainOptions& opt)
{
    opt.validate();
    requirePositive("tauMin [day]", tauMin);
    requireGreaterEqual("tauMax [day]", tauMax, "tauMin", tauMin);
    requirePositive("lambda0 [day]", lambda0);
    const double unitsPerDecade = opt.unitsPerDecade;
    const double eps = 1e-9;
    const long jmin = static_cast<long>(std::floor(unitsPerDecade * std::log10(tauMin / lambda0) + eps));
    const long jmax = static_cast<long>(std::ceil(unitsPerDecade * std::log10(tauMax / lambda0) - eps));
    std::vector<double> tau;
    for (long j = jmin; j <= jmax; ++j) tau.push_back(lambda0 * std::pow(10.0, j / unitsPerDecade));
    return KelvinChain(q2, n, lambda0, std::move(tau), opt);
}

KelvinChain KelvinChain::forAnalysis(double q2, double n, double lambda0, double shortestLag,
                                     double longestLag, const KelvinChainOptions& opt)
{
    opt.validate();
    requirePositive("shortestLag [day]", shortestLag);
    requireGreaterEqual("longestLag [day]", longestLag, "shortestLag", shortestLag);
    return forRange(q2, n, lambda0, shortestLag * std::pow(10.0, -opt.marginBelow),
                    longestLag * std::pow(10.0, opt.marginAbove), opt);
}

double KelvinChain::compliance(double xi) const
{
    requireNonNegative("xi [day]", xi);
    double c = A0_;
    for (std::size_t i = 0; i < tau_.size(); ++i) c += A_[i] * -std::expm1(-xi / tau_[i]);
    return c;
}

double KelvinChain::phi(double xi) const
{
    requireNonNegative("xi [day]", xi);
    return q2_ * std::log1p(std::pow(xi / lambda0_, n_));
}

}  // namespace swelldem::core
