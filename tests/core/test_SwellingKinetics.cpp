// SPDX-License-Identifier: GPL-2.0-or-later
#include "Reference.hpp"
#include "core/SwellingKinetics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <functional>

using namespace swelldem::core;
namespace ref = swelldem::testref;

namespace {

// Classical RK4 of eqs. 5-6 written in the test: dxi/dt = (1 - xi)(xi + c)/(tau_c (1 + c)),
// c = exp(-tau_L/tau_c), tau's Arrhenius-scaled at T(t).
double rk4(double tc0, double tl0, double T0, const std::function<double(double)>& T, double t1, int n)
{
    auto f = [&](double t, double x) {
        const double Tk = T(t);
        const double tc = tc0 * std::exp(5400.0 * (1 / Tk - 1 / T0));
        const double tl = tl0 * std::exp(9400.0 * (1 / Tk - 1 / T0));
        const double c = std::exp(-tl / tc);
        return (1 - x) * (x + c) / (tc * (1 + c));
    };
    double x = 0, t = 0;
    const double h = t1 / n;
    for (int i = 0; i < n; ++i) {
        const double k1 = f(t, x), k2 = f(t + h / 2, x + h / 2 * k1), k3 = f(t + h / 2, x + h / 2 * k2),
                     k4 = f(t + h, x + h * k3);
        x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        t += h;
    }
    return x;
}

}  // namespace

TEST(SwellingKinetics, ClosedFormIsTheSigmoid)
{
    const SwellingKinetics k(50, 100);
    for (double t : {0.0, 1.0, 50.0, 100.0, 365.0, 3650.0}) EXPECT_NEAR(k.xi(t), ref::sigmoid(t, 50, 100), 1e-15);
    EXPECT_EQ(k.xi(0.0), 0.0);
}

TEST(SwellingKinetics, ClosedFormSolvesTheOdeAtConstantTemperature)
{
    for (auto [tc, tl, tEnd] : {std::tuple{50.0, 100.0, 3650.0}, std::tuple{2500.0, 5000.0, 50000.0}}) {
        const SwellingKinetics k(tc, tl);
        const auto T = [](double) { return 293.15; };
        double worst = 0;
        for (double t : {0.25 * tl, tl, 2 * tl, tEnd}) {
            const double x = rk4(tc, tl, 293.15, T, t, 20000);
            worst = std::max(worst, std::fabs(k.xi(t) - x));
            EXPECT_NEAR(k.integrate(0.0, 0.0, t, T), x, 1e-9);  // the ODE integrator of the code
        }
        std::printf("[sigmoid vs RK4 ODE, tau_c = %g] largest |difference| %.2e\n", tc, worst);
        EXPECT_LT(worst, 1e-9);
    }
}

TEST(SwellingKinetics, ArrheniusScaling)
{
    const SwellingKinetics k(50, 100, 293.15);
    const double T = 311.15;  // 38 C
    EXPECT_NEAR(k.tauC(T), 50 * std::exp(5400 * (1 / T - 1 / 293.15)), 1e-12);
    EXPECT_NEAR(k.tauL(T), 100 * std::exp(9400 * (1 / T - 1 / 293.15)), 1e-12);
    EXPECT_LT(k.tauC(T), 50.0);  // hotter: faster
    const auto TT = [=](double) { return T; };
    for (double t : {20.0, 60.0, 200.0}) {
        const double x = rk4(50, 100, 293.15, TT, t, 20000);
        EXPECT_NEAR(k.xiAt(t, T), x, 1e-9);
        EXPECT_NEAR(k.integrate(0.0, 0.0, t, TT), x, 1e-9);
    }
}

TEST(SwellingKinetics, VariableTemperatureHistory)
{
    const SwellingKinetics k(50, 100, 293.15);
    const auto T = [](double t) { return 293.15 + 15.0 * std::sin(2 * M_PI * t / 365.0); };  // seasons
    for (double t : {100.0, 300.0, 1000.0}) {
        const double x = rk4(50, 100, 293.15, T, t, 40000);
        const double y = k.integrate(0.0, 0.0, t, T, 4000);
        EXPECT_NEAR(y, x, 2e-6) << t;
        // restarted integration (step by step) gives the same
        double z = 0, tp = 0;
        for (double tn : {t / 4, t / 2, t}) {
            z = k.integrate(z, tp, tn, T, 2000);
            tp = tn;
        }
        EXPECT_NEAR(z, x, 2e-6);
    }
    // a piecewise-linear table: cooling from 30 C to 10 C
    const std::vector<double> times{0, 200}, temps{303.15, 283.15};
    const auto Tlin = [](double t) { return t >= 200 ? 283.15 : 303.15 - 20.0 * t / 200; };
    EXPECT_NEAR(k.integrate(0.0, 0.0, 400.0, times, temps, 8000), rk4(50, 100, 293.15, Tlin, 400, 40000), 2e-6);
}

TEST(SwellingKinetics, IncrementKeepsPrecisionAndNeverOverflows)
{
    // reference: composite Simpson (long double) of the ODE rate (1 - xi)(xi + c)/(tau_c (1 + c))
    // over [t1, t2] (the exact increment, with no difference of nearly equal numbers)
    const SwellingKinetics k(50, 100);
    const long double tc = 50, tl = 100, c = expl(-tl / tc);
    auto rate = [&](long double s) {
        const long double e = expl(-(s - tl) / tc);
        const long double x = (1 - expl(-s / tc)) / (1 + e);
        const long double oneMinusX = (e + expl(-s / tc)) / (1 + e);
        return oneMinusX * (x + c) / (tc * (1 + c));
    };
    for (double t : {0.0, 1e-3, 1.0, 100.0, 1000.0, 3650.0})
        for (double dt : {1e-9, 1e-6, 1e-2, 10.0, 1e5}) {
            const double t2 = t + dt;
            const long double a = t, b = t2;
            const int panels = 2 * static_cast<int>(std::max(50.0L, 100 * (b - a) / tc));
            const long double h = (b - a) / panels;
            long double sum = rate(a) + rate(b);
            for (int i = 1; i < panels; ++i) sum += (i % 2 ? 4 : 2) * rate(a + i * h);
            const long double d = sum * h / 3;
            const double inc = k.increment(t, t2);
            ASSERT_TRUE(std::isfinite(inc));
            if (d > 1e-300L) {
                EXPECT_NEAR(inc / static_cast<double>(d), 1.0, 1e-9) << t << " " << dt;
            }
        }
    // long times, large latency ratio: no overflow, xi -> 1
    const SwellingKinetics slow(1.0, 600.0);
    EXPECT_EQ(slow.xi(0.0), 0.0);
    EXPECT_GT(slow.xi(1e9), 0.999999);
    EXPECT_TRUE(std::isfinite(slow.increment(0.0, 1e-6)));
    EXPECT_GE(slow.increment(0.0, 1e-6), 0.0);
    EXPECT_NEAR(k.increment(0.0, 1e9), 1.0, 1e-15);
}
