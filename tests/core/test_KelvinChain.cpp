// SPDX-License-Identifier: GPL-2.0-or-later
#include "Reference.hpp"
#include "core/KelvinChain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace swelldem::core;
namespace ref = swelldem::testref;

// Post-Widder orders 2 and 3 written out by hand for Phi = q2 ln(1 + x^n), x = xi/lambda0,
// u = (k tau)^n:  L2 = q2 n u (1 - n + u)/(1+u)^2,
//                 L3 = q2/2 [n^3 u (1-u)/(1+u)^3 - 3 n^2 u/(1+u)^2 + 2 n u/(1+u)].
TEST(KelvinChain, SpectrumOrders2And3MatchHandDerivation)
{
    const double q2 = 2.5, n = 0.1;
    for (double tau : {1e-4, 0.3, 1.0, 50.0, 1e5}) {
        const double u2 = std::pow(2 * tau, n), u3 = std::pow(3 * tau, n);
        const double L2 = q2 * n * u2 * (1 - n + u2) / ((1 + u2) * (1 + u2));
        const double L3 = 0.5 * q2 *
                          (n * n * n * u3 * (1 - u3) / std::pow(1 + u3, 3) - 3 * n * n * u3 / std::pow(1 + u3, 2) +
                           2 * n * u3 / (1 + u3));
        EXPECT_NEAR(KelvinChain::spectrum(tau, q2, n, 1.0, 2) / L2, 1.0, 1e-12);
        EXPECT_NEAR(KelvinChain::spectrum(tau, q2, n, 1.0, 3) / L3, 1.0, 1e-12);
    }
}

// The closed-form integral below tau equals numerical quadrature of the spectrum over ln tau.
TEST(KelvinChain, SpectrumIntegralMatchesQuadrature)
{
    for (int k : {1, 2, 3, 4})
        for (bool rich : {false, true}) {
            if (rich && k > 4) continue;
            const double tau = 0.05;
            const double num = ref::integrate(
                [&](double y) { return KelvinChain::spectrum(std::exp(y), 1.0, 0.1, 1.0, k, rich); }, -400.0,
                std::log(tau), 4000);
            EXPECT_NEAR(KelvinChain::spectrumIntegralBelow(tau, 1.0, 0.1, 1.0, k, rich) / num, 1.0, 1e-6)
                << "k=" << k << " richardson=" << rich;
        }
}

// The chain reproduces Phi over the analysis span; prints the accuracy for several sizes.
TEST(KelvinChain, ReproducesPhiOverTheSpan)
{
    std::printf("[chain vs Phi, xi in 0.01..1e4 d]  order richardson units/decade  size  max rel error\n");
    double defaultErr = 1;
    for (int k : {2, 3})
        for (bool rich : {false, true})
            for (double upd : {0.5, 1.0, 2.0}) {
                KelvinChainOptions o;
                o.order = k;
                o.richardson = rich;
                o.unitsPerDecade = upd;
                const KelvinChain c = KelvinChain::forAnalysis(1.0, 0.1, 1.0, 0.01, 1e4, o);
                double worst = 0;
                for (double lx = -2; lx <= 4.0001; lx += 0.02) {
                    const double xi = std::pow(10.0, lx);
                    const double phi = std::log1p(std::pow(xi, 0.1));  // written out, not c.phi
                    worst = std::max(worst, std::fabs(c.compliance(xi) / phi - 1));
                }
                for (double a : c.A()) EXPECT_GT(a, 0.0);
                EXPECT_GT(c.A0(), 0.0);
                std::printf("  %d %d %4.1f  %3zu  %.4f %%\n", k, rich, upd, c.size(), 100 * worst);
                if (k == 2 && rich && upd == 1.0) defaultErr = worst;
            }
    EXPECT_LT(defaultErr, 0.005);  // default chain: < 0.5 %
}

TEST(KelvinChain, RangeFollowsTheAnalysisAndGivenTimesAreKept)
{
    const KelvinChain c = KelvinChain::forAnalysis(1.0, 0.1, 1.0, 0.05, 3650.0);
    EXPECT_LE(c.tau().front(), 0.005 * (1 + 1e-12));
    EXPECT_GE(c.tau().back(), 36500.0 * (1 - 1e-12));
    EXPECT_LT(c.tau().front(), 0.05);
    for (std::size_t i = 1; i < c.size(); ++i) EXPECT_NEAR(c.tau()[i] / c.tau()[i - 1], 10.0, 1e-9);
    const KelvinChain g(1.0, 0.1, 1.0, {0.1, 1.0, 30.0});
    EXPECT_EQ(g.size(), 3u);
    EXPECT_EQ(g.tau()[2], 30.0);
    KelvinChainOptions dense;
    dense.unitsPerDecade = 2;
    EXPECT_EQ(KelvinChain::forRange(1.0, 0.1, 1.0, 1e-2, 1e2, dense).size(), 9u);
}
