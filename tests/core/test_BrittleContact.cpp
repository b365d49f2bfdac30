// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/BrittleContact.hpp"
#include "core/ContactLaw.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace swelldem::core;

namespace {
BrittleStrength mortarStrength(bool shear)
{
    BrittleStrength s;
    s.damage = true;
    s.tensileStrength = 4e6;
    s.shearFailure = shear;
    s.cohesion = 8e6;
    s.frictionAngle = 0.5;
    s.residualFrictionAngle = 0.4;
    return s;
}
}  // namespace

TEST(BrittleContact, TensionCutOffAtFtTimesArea)
{
    const BrittleStrength s = mortarStrength(false);
    const double A = 7.4e-4;  // paper's mean facet: Fn,max = 2.96 kN
    EXPECT_NEAR(BrittleContact::maxTension(s, A), 2960.0, 1e-9);
    EXPECT_EQ(BrittleContact::check(s, A, 2959.0, 0.0), FailureMode::None);
    EXPECT_EQ(BrittleContact::check(s, A, 2961.0, 0.0), FailureMode::Tension);
    EXPECT_EQ(BrittleContact::check(s, A, -1e9, 1e9), FailureMode::None);  // shear failure off
    BrittleStrength off = s;
    off.damage = false;
    EXPECT_EQ(BrittleContact::check(off, A, 1e12, 1e12), FailureMode::None);
}

TEST(BrittleContact, MohrCoulombShear)
{
    const BrittleStrength s = mortarStrength(true);
    const double A = 1e-3, Fn = -2000.0;
    const double cap = 8e6 * A + std::tan(0.5) * 2000.0;
    EXPECT_NEAR(BrittleContact::shearCapacityIntact(s, A, Fn), cap, 1e-9);
    EXPECT_EQ(BrittleContact::check(s, A, Fn, 0.999 * cap), FailureMode::None);
    EXPECT_EQ(BrittleContact::check(s, A, Fn, -1.001 * cap), FailureMode::Shear);
    // tension reduces nothing below cohesion (max(-Fn, 0))
    EXPECT_NEAR(BrittleContact::shearCapacityIntact(s, A, 1000.0), 8e6 * A, 1e-9);
    EXPECT_EQ(BrittleContact::check(s, A, 5000.0, 0.0), FailureMode::Tension);  // tension first
}

TEST(BrittleContact, BrokenStateNoTensionCoulombInCompression)
{
    const BrittleStrength s = mortarStrength(false);
    double Fn, Fs;
    BrittleContact::brokenForces(s, 500.0, 300.0, Fn, Fs);
    EXPECT_EQ(Fn, 0.0);
    EXPECT_EQ(Fs, 0.0);
    BrittleContact::brokenForces(s, -1000.0, 600.0, Fn, Fs);
    EXPECT_EQ(Fn, -1000.0);
    EXPECT_NEAR(Fs, std::tan(0.4) * 1000.0, 1e-9);
    BrittleContact::brokenForces(s, -1000.0, -600.0, Fn, Fs);
    EXPECT_NEAR(Fs, -std::tan(0.4) * 1000.0, 1e-9);
    BrittleContact::brokenForces(s, -1000.0, -100.0, Fn, Fs);
    EXPECT_EQ(Fs, -100.0);
}

// Through the contact law: break in tension, the crack must close before compression returns.
TEST(BrittleContact, CrackMustReCloseBeforeCompression)
{
    ContactKindParams p;
    p.behaviour = Behaviour::Elastic;
    p.contactModulus = 30e9;
    p.shearRatio = 0.3;
    p.strength = mortarStrength(false);
    ContactLaw law(p);
    const ContactGeometry g{7.4e-4, 0.8e-3};
    ContactState s;
    law.initState(s);
    const double kn = 30e9 * 7.4e-4 / 0.8e-3;
    law.beginStep(0, 1);
    law.beginContactStep(g, s);
    // below the strength: elastic
    EXPECT_NEAR(law.trial(g, s, 2900.0 / kn, 0).Fn, 2900.0, 1e-6);
    EXPECT_FALSE(s.trial.broken);
    // above: breaks, transmits nothing, and stays broken in this step even if unloaded
    const double uBreak = 3000.0 / kn;
    EXPECT_EQ(law.trial(g, s, uBreak, 0).Fn, 0.0);
    EXPECT_TRUE(s.trial.broken);
    EXPECT_EQ(s.trial.mode, FailureMode::Tension);
    EXPECT_EQ(law.trial(g, s, 0.5 * uBreak, 0).Fn, 0.0);
    law.trial(g, s, uBreak, 0);
    law.commit(g, s);
    EXPECT_TRUE(s.committed.broken);
    EXPECT_NEAR(s.committed.FnHat, 3000.0, 1e-6);
    // next step: closing by less than the opening keeps Fn = 0
    law.beginStep(1, 2);
    law.beginContactStep(g, s);
    EXPECT_EQ(law.trial(g, s, -0.9 * uBreak, 0).Fn, 0.0);
    // closing beyond it gives compression k (u - u_open)
    EXPECT_NEAR(law.trial(g, s, -1.5 * uBreak, 0).Fn, -1500.0, 1e-6);
    // shear bounded by the residual Coulomb cone
    const ContactForces& f = law.trial(g, s, -1.5 * uBreak, 1.0);
    EXPECT_NEAR(f.Fs, std::tan(0.4) * 1500.0, 1e-6);
    // no tension ever again
    EXPECT_EQ(law.trial(g, s, 10 * uBreak, 0).Fn, 0.0);
}

TEST(BrittleContact, ShearBreakThroughContactLaw)
{
    ContactKindParams p;
    p.contactModulus = 30e9;
    p.shearRatio = 0.3;
    p.strength = mortarStrength(true);
    ContactLaw law(p);
    const ContactGeometry g{1e-3, 1e-3};
    ContactState s;
    law.initState(s);
    law.beginStep(0, 1);
    law.beginContactStep(g, s);
    const double ks = 0.3 * 30e9;
    const double Fn = -1000.0, kn = 30e9;
    const double cap = 8e6 * 1e-3 + std::tan(0.5) * 1000.0;
    law.trial(g, s, Fn / kn, 0.99 * cap / ks);
    EXPECT_FALSE(s.trial.broken);
    const ContactForces& f = law.trial(g, s, Fn / kn, 1.01 * cap / ks);
    EXPECT_TRUE(f.broken);
    EXPECT_EQ(f.mode, FailureMode::Shear);
    EXPECT_NEAR(f.Fn, Fn, 1e-6);
    EXPECT_NEAR(f.Fs, std::tan(0.4) * 1000.0, 1e-6);
}
