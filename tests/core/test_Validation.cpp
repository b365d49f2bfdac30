// SPDX-License-Identifier: GPL-2.0-or-later
// Every validation error path: the message names the parameter, the value and the allowed range.
#include "core/B3Compliance.hpp"
#include "core/BrittleContact.hpp"
#include "core/ContactLaw.hpp"
#include "core/ContactKindParams.hpp"
#include "core/KelvinChain.hpp"
#include "core/LogTimes.hpp"
#include "core/SolidificationCreep.hpp"
#include "core/SwellingKinetics.hpp"
#include "core/Validate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

using namespace swelldem::core;

namespace {

// Expects std::invalid_argument whose message is
// "swelldem: <param> = <value> is out of range; allowed: <...range...>".
void expectInvalid(const std::function<void()>& f, const std::string& param, const std::string& value,
                   const std::string& rangeFragment)
{
    try {
        f();
        ADD_FAILURE() << "no exception for " << param;
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        const std::string head = "swelldem: " + param + " = " + value + " is out of range; allowed: ";
        EXPECT_EQ(msg.rfind(head, 0), 0u) << msg;
        EXPECT_NE(msg.find(rangeFragment, head.size()), std::string::npos) << msg;
    }
}

B3Params with(void (*edit)(B3Params&))
{
    B3Params p = B3Params::mortarM6();
    edit(p);
    return p;
}

}  // namespace

TEST(Validation, HelperFormat)
{
    expectInvalid([] { requirePositive("x [m]", -2.5); }, "x [m]", "-2.5", "0 < x [m] < inf");
    expectInvalid([] { requireNonNegative("y", -1e-3); }, "y", "-0.001", "0 <= y < inf");
    expectInvalid([] { requireOpenInterval("z", 1.0, 0.0, 1.0); }, "z", "1", "0 < z < 1");
    expectInvalid([] { requireGreater("t", 3.0, "t'", 7.0); }, "t", "3", "t > t' = 7");
    expectInvalid([] { requirePositive("w", std::nan("")); }, "w", "nan", "0 < w");
    expectInvalid([] { requirePositive("w", INFINITY); }, "w", "inf", "0 < w");
    EXPECT_NO_THROW(requirePositive("x", 1e-300));
}

TEST(Validation, B3Params)
{
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.q1 = -1e-12; })); }, "q1 [1/Pa]", "-1e-12", "0 < q1");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.q2 = 0; })); }, "q2 [1/Pa]", "0", "0 < q2");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.q3 = -1; })); }, "q3 [1/Pa]", "-1", "0 <= q3");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.q4 = -1; })); }, "q4 [1/Pa]", "-1", "0 <= q4");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.n = 1; })); }, "n", "1", "0 < n < 1");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.m = 0; })); }, "m", "0", "0 < m < 1");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.lambda0 = 0; })); }, "lambda0 [day]", "0", "0 < lambda0");
    expectInvalid([] { B3Compliance(with([](B3Params& p) { p.elasticLag = -0.01; })); }, "elasticLag [day]", "-0.01",
                  "0 < elasticLag");
    const B3Compliance b(B3Params::mortarM6());
    expectInvalid([&] { b.J(5, 7); }, "t [day]", "5", "t [day] > t' = 7");
    expectInvalid([&] { b.J(7, 7); }, "t [day]", "7", "t [day] > t' = 7");
    expectInvalid([&] { b.J(5, 0); }, "t' [day]", "0", "0 < t' [day]");
    expectInvalid([&] { b.Q(5, -1); }, "t' [day]", "-1", "0 < t' [day]");
    expectInvalid([&] { b.E(0); }, "t [day]", "0", "0 < t [day]");
    expectInvalid([&] { b.invV(-3); }, "t [day]", "-3", "0 < t [day]");
    expectInvalid([&] { b.phi(-3); }, "xi [day]", "-3", "0 <= xi [day]");
}

TEST(Validation, KelvinChain)
{
    expectInvalid([] { KelvinChain(0, 0.1, 1, {1.0}); }, "q2 [1/Pa]", "0", "0 < q2");
    expectInvalid([] { KelvinChain(1, 1.5, 1, {1.0}); }, "n", "1.5", "0 < n < 1");
    expectInvalid([] { KelvinChain(1, 0.1, -1, {1.0}); }, "lambda0 [day]", "-1", "0 < lambda0");
    expectInvalid([] { KelvinChain(1, 0.1, 1, {}); }, "number of retardation times", "0", ">= 1");
    expectInvalid([] { KelvinChain(1, 0.1, 1, {-1.0}); }, "tau[0] [day]", "-1", "0 < tau[0]");
    expectInvalid([] { KelvinChain(1, 0.1, 1, {1.0, 1.0}); }, "tau[1] [day]", "1", "tau[1] [day] > tau[0] = 1");
    KelvinChainOptions o;
    o.unitsPerDecade = 0;
    expectInvalid([&] { o.validate(); }, "unitsPerDecade", "0", "0.1 <= unitsPerDecade <= 20");
    o = {};
    o.order = 5;
    expectInvalid([&] { o.validate(); }, "order (Post-Widder)", "5", "1 <= order <= 4");
    o = {};
    o.marginAbove = -1;
    expectInvalid([&] { o.validate(); }, "kelvinMarginAbove [decades]", "-1", "0 <= kelvinMarginAbove <= 6");
    o.marginAbove = 6.5;
    expectInvalid([&] { o.validate(); }, "kelvinMarginAbove [decades]", "6.5", "0 <= kelvinMarginAbove <= 6");
    o.marginAbove = std::nan("");
    expectInvalid([&] { o.validate(); }, "kelvinMarginAbove [decades]", "nan", "0 <= kelvinMarginAbove <= 6");
    o = {};
    o.marginBelow = -1;
    expectInvalid([&] { o.validate(); }, "marginBelow [decades]", "-1", "0 <= marginBelow");
    expectInvalid([] { KelvinChain::forRange(1, 0.1, 1, 0, 10); }, "tauMin [day]", "0", "0 < tauMin");
    expectInvalid([] { KelvinChain::forRange(1, 0.1, 1, 10, 1); }, "tauMax [day]", "1", "tauMax [day] >= tauMin = 10");
    expectInvalid([] { KelvinChain::forAnalysis(1, 0.1, 1, -1, 10); }, "shortestLag [day]", "-1", "0 < shortestLag");
    expectInvalid([] { KelvinChain::forAnalysis(1, 0.1, 1, 5, 1); }, "longestLag [day]", "1", ">= shortestLag = 5");
    expectInvalid([] { KelvinChain::spectrum(-1, 1, 0.1, 1, 2); }, "tau [day]", "-1", "0 < tau");
    expectInvalid([] { KelvinChain::spectrum(1, 1, 0.1, 1, 9); }, "order (Post-Widder)", "9", "1 <= order <= 8");
    const KelvinChain c(1, 0.1, 1, {1.0});
    expectInvalid([&] { c.compliance(-1); }, "xi [day]", "-1", "0 <= xi");
}

TEST(Validation, SolidificationCreep)
{
    expectInvalid([] { SolidificationCreep(with([](B3Params& p) { p.q2 = -1; }), 0.01, 1e4); }, "q2 [1/Pa]", "-1",
                  "0 < q2");
    const SolidificationCreep c(B3Params::mortarM6(), 0.01, 1e4);
    expectInvalid([&] { c.factors(0, 1); }, "tPrev [day]", "0", "0 < tPrev");
    expectInvalid([&] { c.factors(2, 1); }, "t [day]", "1", "t [day] >= tPrev = 2");
}

TEST(Validation, SwellingKinetics)
{
    expectInvalid([] { SwellingKinetics(0, 100); }, "tau_c [day]", "0", "0 < tau_c");
    expectInvalid([] { SwellingKinetics(50, -1); }, "tau_L [day]", "-1", "0 <= tau_L <= 700 tau_c = 35000");
    expectInvalid([] { SwellingKinetics(1, 701); }, "tau_L [day]", "701", "700 tau_c = 700");
    expectInvalid([] { SwellingKinetics(50, 100, -273); }, "T0 [K]", "-273", "0 < T0");
    expectInvalid([] { SwellingKinetics(50, 100, 293, -1); }, "U_c [K]", "-1", "0 <= U_c");
    expectInvalid([] { SwellingKinetics(50, 100, 293, 5400, -1); }, "U_L [K]", "-1", "0 <= U_L");
    const SwellingKinetics k(50, 100);
    expectInvalid([&] { k.xi(-1); }, "t [day]", "-1", "0 <= t");
    expectInvalid([&] { k.xiAt(1, 0); }, "T [K]", "0", "0 < T");
    expectInvalid([&] { k.increment(-1, 2); }, "t1 [day]", "-1", "0 <= t1");
    expectInvalid([&] { k.increment(3, 2); }, "t2 [day]", "2", "t2 [day] >= t1 = 3");
    expectInvalid([&] { k.rate(1.5, 300); }, "xi", "1.5", "0 <= xi <= 1");
    const auto T = [](double) { return 293.0; };
    expectInvalid([&] { k.integrate(-0.1, 0, 1, T); }, "xi0", "-0.1", "0 <= xi0 <= 1");
    expectInvalid([&] { k.integrate(0, -1, 1, T); }, "t0 [day]", "-1", "0 <= t0");
    expectInvalid([&] { k.integrate(0, 2, 1, T); }, "t1 [day]", "1", ">= t0 = 2");
    expectInvalid([&] { k.integrate(0, 0, 1, [](double) { return -5.0; }); }, "T [K]", "-5", "0 < T");
    expectInvalid([&] { k.integrate(0, 0, 1, {0.0, 1.0}, {300.0}); }, "len(temperatures)", "1", "len(temperatureDays) = 2");
    expectInvalid([&] { k.integrate(0, 0, 1, {0.0, 1.0}, {300.0, 0.0}); }, "temperatures[1] [K]", "0",
                  "0 < temperatures[1] <= 373.15 [K]");
    expectInvalid([&] { k.integrate(0, 0, 1, {0.0, 0.0}, {300.0, 300.0}); }, "temperatureDays[1] [day]", "0",
                  "temperatureDays[1] [day] > temperatureDays[0] = 0");
}

TEST(Validation, BrittleStrength)
{
    BrittleStrength s;
    s.damage = true;
    s.tensileStrength = 0;
    expectInvalid([&] { s.validate(); }, "tensileStrength f_t [Pa]", "0", "0 < tensileStrength");
    s.tensileStrength = 4e6;
    s.cohesion = -1;
    expectInvalid([&] { s.validate(); }, "cohesion c [Pa]", "-1", "0 <= cohesion");
    s.cohesion = 0;
    s.frictionAngle = 2;
    expectInvalid([&] { s.validate(); }, "frictionAngle phi [rad]", "2", "0 <= phi < pi/2");
    s.frictionAngle = 0.5;
    s.residualFrictionAngle = -0.1;
    expectInvalid([&] { s.validate(); }, "residualFrictionAngle [rad]", "-0.1", "0 <= phi_res < pi/2");
}

TEST(Validation, ContactKindGeometryAndLaw)
{
    ContactKindParams p;
    p.contactModulus = 0;
    expectInvalid([&] { ContactLaw l(p); }, "young (contact modulus E_c) [Pa]", "0", "0 < young");
    p.contactModulus = 1e10;
    p.shearRatio = -0.2;
    expectInvalid([&] { ContactLaw l(p); }, "shearRatio alpha [-]", "-0.2", "0 < shearRatio");
    p.shearRatio = 0.2;
    p.swelling = true;
    p.swellingDisplacementInf = -1e-6;
    expectInvalid([&] { ContactLaw l(p); }, "swellDispInf [m]", "-1e-06", "0 <= swellDispInf");
    p.swellingDisplacementInf = 1e-6;
    p.swellingStrainInf = 1e-3;
    expectInvalid([&] { ContactLaw l(p); }, "swellingStrainInf [-]", "0.001", "give one of the two");
    p.swellingStrainInf = 0;
    p.tauC = -5;
    expectInvalid([&] { ContactLaw l(p); }, "tau_c [day]", "-5", "0 < tau_c");
    p.tauC = 50;
    p.behaviour = Behaviour::Viscoelastic;
    p.b3.q1 = 0;
    expectInvalid([&] { ContactLaw l(p); }, "q1 [1/Pa]", "0", "0 < q1");
    p.b3 = B3Params::mortarM6();
    p.chain.unitsPerDecade = 100;
    expectInvalid([&] { ContactLaw l(p); }, "unitsPerDecade", "100", "0.1 <= unitsPerDecade <= 20");
    p.chain.unitsPerDecade = 1;
    ContactLaw law(p);
    expectInvalid([&] { law.beginStep(0, 1); }, "tPrev [day]", "0", "0 < tPrev");
    expectInvalid([&] { law.beginStep(5, 1); }, "t [day]", "1", "t [day] >= tPrev = 5");
    law.beginStep(1, 2);
    ContactState s;
    law.initState(s);
    expectInvalid([&] { law.beginContactStep(ContactGeometry{0, 1e-3}, s); }, "area [m2]", "0", "0 < area");
    expectInvalid([&] { law.beginContactStep(ContactGeometry{1e-3, -1}, s); }, "length [m]", "-1", "0 < length");
    ContactState fresh;  // a contact new to the law gets its hidden variables
    law.beginContactStep(ContactGeometry{1e-3, 1e-3}, fresh);
    EXPECT_EQ(fresh.gamma.size(), law.hiddenStateSize());
    ContactState other;  // hidden variables of another chain: refused
    other.gamma.assign(law.hiddenStateSize() + 2, 0.0);
    expectInvalid([&] { law.beginContactStep(ContactGeometry{1e-3, 1e-3}, other); }, "hidden creep state size of a contact",
                  std::to_string(law.hiddenStateSize() + 2), "Kelvin chain changed");
}

TEST(Validation, TemperatureHistoryAndThermalCreep)
{
    ContactKindParams p;
    p.temperatureDays = {0.0, 10.0};
    p.temperatures = {293.15, 400.0};
    expectInvalid([&] { p.validate(); }, "temperatures[1] [K]", "400", "0 < temperatures[1] <= 373.15 [K]");
    p.temperatures = {-1.0, 293.15};
    expectInvalid([&] { p.validate(); }, "temperatures[0] [K]", "-1", "0 < temperatures[0] <= 373.15 [K]");
    p.temperatures = {293.15, 293.15};
    p.temperatureDays = {10.0, 5.0};
    expectInvalid([&] { p.validate(); }, "temperatureDays[1] [day]", "5", "temperatureDays[1] [day] > temperatureDays[0] = 10");
    p.temperatureDays = {-2.0, 5.0};
    expectInvalid([&] { p.validate(); }, "temperatureDays[0] [day]", "-2", "0 <= temperatureDays[0] [day] < inf");
    p.temperatureDays = {0.0, 5.0, 9.0};
    expectInvalid([&] { p.validate(); }, "len(temperatures)", "2", "len(temperatureDays) = 3");
    p.temperatureDays = {0.0, 5.0};
    p.validate();  // a good history
    p.behaviour = Behaviour::Viscoelastic;
    p.thermal.T0 = 0;
    expectInvalid([&] { p.validate(); }, "creepReferenceTemperature [K]", "0", "0 < creepReferenceTemperature <= 373.15 [K]");
    p.thermal.T0 = 293.15;
    p.thermal.Ur = -5;
    expectInvalid([&] { p.validate(); }, "creepUr [K]", "-5", "0 <= creepUr [K] < inf");
    p.thermal.on = false;  // switched off, its values are not used
    p.validate();
}

TEST(Validation, LogTimes)
{
    expectInvalid([] { logTimes(0, 10, 5); }, "tStart [day]", "0", "0 < tStart");
    expectInvalid([] { logTimes(10, 10, 5); }, "tEnd [day]", "10", "tEnd [day] > tStart = 10");
    expectInvalid([] { logTimes(1, 10, 0); }, "stepsPerDecade", "0", "0 < stepsPerDecade <= 10000");
    expectInvalid([] { logTimes(1, 10, 5, {20.0}); }, "extraTimes[0] [day]", "20", "1 <= t <= 10");
}

TEST(LogTimes, EvenlySpacedInLogTimeWithExtras)
{
    const auto t = logTimes(1, 1000, 5);
    ASSERT_EQ(t.size(), 16u);
    EXPECT_EQ(t.front(), 1.0);
    EXPECT_EQ(t.back(), 1000.0);
    for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] / t[i - 1], std::pow(10.0, 0.2), 1e-12);
    const auto u = logTimes(1, 3650, 2, {28.0, 10.0, 3650.0});
    EXPECT_EQ(u.back(), 3650.0);
    int n28 = 0, n10 = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        if (i) {
            EXPECT_GT(u[i], u[i - 1]);
        }
        n28 += u[i] == 28.0;
        n10 += std::fabs(u[i] - 10.0) < 1e-9;
    }
    EXPECT_EQ(n28, 1);
    EXPECT_EQ(n10, 1);  // 10 is on the grid already: not duplicated
}
