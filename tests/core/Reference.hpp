// SPDX-License-Identifier: GPL-2.0-or-later
// Independent references for the core's tests. Nothing here calls the code under test: the B3
// formula, the exact solidification integral, the sigmoid and a Volterra step-by-step solver are
// written out again from the formulas.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

namespace swelldem::testref {

struct B3 {
    double q1, q2, q3, q4;  // 1/Pa; n = 0.1, m = 0.5, lambda0 = 1 day
};

// Paper Table 3.3, mortar M6, 1e-6/MPa -> 1/Pa.
inline B3 mortar() { return {6.7e-12, 108.1e-12, 44.2e-12, 14.3e-12}; }
inline B3 itz() { return {19.3e-12, 194.6e-12, 72.9e-12, 7.5e-12}; }

// Bazant's approximation of Q written from the B3 papers (n = 0.1, m = 0.5).
inline double qApprox(double t, double tp)
{
    const double qf = 1.0 / (0.086 * std::pow(tp, 2.0 / 9.0) + 1.21 * std::pow(tp, 4.0 / 9.0));
    const double z = std::log(1.0 + std::pow(t - tp, 0.1)) / std::sqrt(tp);
    const double r = 1.7 * std::pow(tp, 0.12) + 8.0;
    if (z <= 0) return 0.0;
    return qf * std::pow(1.0 + std::pow(qf / z, r), -1.0 / r);
}

inline double jB3(const B3& b, double t, double tp)
{
    return b.q1 + b.q2 * qApprox(t, tp) + b.q3 * std::log(1.0 + std::pow(t - tp, 0.1)) + b.q4 * std::log(t / tp);
}

// Gauss-Legendre nodes/weights on [-1, 1], 8 points.
inline const double* gl8x() { static const double x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498, 0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363}; return x; }
inline const double* gl8w() { static const double w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620, 0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763}; return w; }

// Composite 8-point Gauss-Legendre of f on [a, b] with `panels` panels.
inline double integrate(const std::function<double(double)>& f, double a, double b, int panels)
{
    const double* x = gl8x();
    const double* w = gl8w();
    const double h = (b - a) / panels;
    double s = 0;
    for (int p = 0; p < panels; ++p) {
        const double c = a + (p + 0.5) * h;
        for (int i = 0; i < 8; ++i) s += w[i] * f(c + 0.5 * h * x[i]);
    }
    return 0.5 * h * s;
}

// Exact solidification integral Q(t,t') = int_{t'}^{t} tau^-m dPhi(tau - t'), Phi = ln(1 + x^n),
// with s = x^n: Q = int_0^{(t-t')^n} (t' + s^(1/n))^(-m) / (1 + s) ds  (smooth integrand).
inline double qExact(double t, double tp, double n = 0.1, double m = 0.5)
{
    const double S = std::pow(t - tp, n);
    return integrate([&](double s) { return std::pow(tp + std::pow(s, 1.0 / n), -m) / (1.0 + s); }, 0.0, S, 200);
}

// J with the exact solidification integral instead of Bazant's approximation.
inline double jExact(const B3& b, double t, double tp)
{
    return b.q1 + b.q2 * qExact(t, tp) + b.q3 * std::log(1.0 + std::pow(t - tp, 0.1)) + b.q4 * std::log(t / tp);
}

// Larive's sigmoid written directly.
inline double sigmoid(double t, double tc, double tl)
{
    return (1.0 - std::exp(-t / tc)) / (1.0 + std::exp(-(t - tl) / tc));
}

// Step-by-step solution of the Volterra equation eps(t_i) = int_{t_0}^{t_i} J(t_i, tau) dsigma(tau)
// on the grid t_0 < t_1 < ... : a jump of sigma at t_0 (from 0 to sigma_0 so that eps(t_0) is
// matched) and sigma linear on each interval; the kernel is averaged over each interval by
// Gauss-Legendre (J(t, t) must return the instantaneous compliance; for the interval ending at t_i with the substitution tau = t_i - h w^10, which
// makes the (t - tau)^0.1 behaviour smooth). Returns sigma(t_i).
inline std::vector<double> volterraStress(const std::function<double(double, double)>& J,
                                          const std::vector<double>& t, const std::vector<double>& eps)
{
    const std::size_t M = t.size();
    std::vector<double> dsig(M, 0.0), sig(M, 0.0);
    const double* x = gl8x();
    const double* w = gl8w();
    auto avgJ = [&](std::size_t i, std::size_t j) {  // average of J(t_i, .) over [t_{j-1}, t_j]
        const double a = t[j - 1], b = t[j], h = b - a;
        double s = 0;
        if (j == i) {
            for (int k = 0; k < 8; ++k) {
                const double ww = 0.5 * (x[k] + 1.0);
                s += 0.5 * w[k] * J(t[i], t[i] - h * std::pow(ww, 10)) * 10.0 * std::pow(ww, 9);
            }
            return s;
        }
        for (int k = 0; k < 8; ++k) s += 0.5 * w[k] * J(t[i], a + 0.5 * h * (x[k] + 1.0));
        return s;
    };
    // jump at t_0: J(t_0, t_0) must be the instantaneous compliance (q1 for B3)
    dsig[0] = eps[0] / J(t[0], t[0]);
    sig[0] = dsig[0];
    for (std::size_t i = 1; i < M; ++i) {
        double rhs = eps[i] - dsig[0] * J(t[i], t[0]);
        for (std::size_t j = 1; j < i; ++j) rhs -= dsig[j] * avgJ(i, j);
        dsig[i] = rhs / avgJ(i, i);
        sig[i] = sig[i - 1] + dsig[i];
    }
    return sig;
}

// Grid t0 + lags, lags log-spaced (perDecade a decade) from lagMin to lagMax, preceded by t0.
inline std::vector<double> lagGrid(double t0, double lagMin, double lagMax, int perDecade)
{
    std::vector<double> g{t0};
    const int n = static_cast<int>(std::lround(std::log10(lagMax / lagMin) * perDecade));
    for (int k = 0; k <= n; ++k) g.push_back(t0 + lagMin * std::pow(10.0, double(k) / perDecade));
    return g;
}

// Grid log-spaced in t itself from t0 to t1 (perDecade a decade, t1 included).
inline std::vector<double> logGrid(double t0, double t1, int perDecade)
{
    std::vector<double> g;
    const int n = static_cast<int>(std::ceil(std::log10(t1 / t0) * perDecade - 1e-9));
    for (int k = 0; k < n; ++k) g.push_back(t0 * std::pow(10.0, double(k) / perDecade));
    g.push_back(t1);
    return g;
}

// Index of the grid point closest to x (relative tolerance check left to the caller).
inline std::size_t nearest(const std::vector<double>& g, double x)
{
    std::size_t best = 0;
    for (std::size_t i = 1; i < g.size(); ++i)
        if (std::fabs(g[i] - x) < std::fabs(g[best] - x)) best = i;
    return best;
}

}  // namespace swelldem::testref
