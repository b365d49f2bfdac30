// SPDX-License-Identifier: GPL-2.0-or-later
// The shear of a 3D contact: two components along two orthogonal tangents of its facet, each with
// the creep of the 2D one, and the strength and the Coulomb cone of their magnitude.
#include "core/ContactLaw.hpp"
#include "core/LogTimes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

using namespace swelldem::core;

namespace {
ContactKindParams viscoelasticMortar()
{
    ContactKindParams p;
    p.behaviour = Behaviour::Viscoelastic;
    p.contactModulus = 25e9;
    p.b3 = B3Params::mortarM6();
    p.shearRatio = 0.25;
    return p;
}

ContactKindParams brittle(bool shearFailure)
{
    ContactKindParams p;
    p.contactModulus = 30e9;
    p.shearRatio = 0.3;
    p.strength.damage = true;
    p.strength.tensileStrength = 4e6;
    p.strength.shearFailure = shearFailure;
    p.strength.cohesion = 8e6;
    p.strength.frictionAngle = 0.5;
    p.strength.residualFrictionAngle = 0.4;
    return p;
}

ContactGeometry geometry3d(double area, double length)
{
    ContactGeometry g{area, length};
    g.shearComponents = 2;
    return g;
}
}  // namespace

TEST(Shear3D, EachComponentCreepsAsTheNormalPerUnitShearRatio)
{
    // An opening and a slip of the same strain held from t0: with the shear's compliance that of the
    // normal over alpha (paper 2.3), (Fs, Fs2) = alpha Fn (cos a, sin a) at every time, Fn being the
    // relaxation that the Volterra test of the normal direction checks.
    ContactLaw law(viscoelasticMortar());
    const ContactGeometry g = geometry3d(7.4e-4, 0.794e-3);
    ContactState s;
    law.initState(s, 2);
    ASSERT_EQ(s.gamma.size(), 3 * law.chainSize());
    const double a = 0.7, u = 1e-7;
    const auto times = logTimes(10, 1000, 5);
    law.beginStep(times[0], times[0]);
    law.beginContactStep(g, s);
    law.trial(g, s, u, u * std::cos(a), u * std::sin(a));
    law.commit(g, s);
    const double F0 = s.committed.Fn;
    for (std::size_t i = 1; i < times.size(); ++i) {
        law.beginStep(times[i - 1], times[i]);
        law.beginContactStep(g, s);
        law.trial(g, s, 0, 0, 0);
        law.commit(g, s);
        const double Fn = s.committed.Fn;
        // measured: 2e-16 relative (round-off); bound 1e-12
        EXPECT_NEAR(s.committed.Fs, 0.25 * Fn * std::cos(a), 1e-12 * Fn);
        EXPECT_NEAR(s.committed.Fs2, 0.25 * Fn * std::sin(a), 1e-12 * Fn);
    }
    EXPECT_LT(s.committed.Fn, 0.8 * F0);  // it relaxed
}

TEST(Shear3D, ASecondComponentAtZeroIsThe2DContactToTheBit)
{
    // What keeps a 2D run's results unchanged: the first component's arithmetic is the scalar one.
    ContactKindParams p = viscoelasticMortar();
    p.strength = brittle(false).strength;
    p.swelling = true;
    p.swellingDisplacementInf = 2e-6;
    p.tauC = 50;
    p.tauL = 100;
    ContactLaw law(p);
    const ContactGeometry g2{7.4e-4, 0.794e-3};
    ContactGeometry g3 = g2;
    g3.shearComponents = 2;
    ContactState s2, s3;
    law.initState(s2, 1);
    law.initState(s3, 2);
    const auto times = logTimes(1, 3650, 4);
    bool broke = false;
    for (std::size_t i = 1; i < times.size(); ++i) {
        law.beginStep(times[i - 1], times[i]);
        law.beginContactStep(g2, s2);
        law.beginContactStep(g3, s3);
        // opening to a break, then closing to compression: the broken contact's Coulomb cone
        const double duN = i < 6 ? 1e-7 : -2e-7, duS = 3e-8 * std::sin(double(i));
        const ContactForces& f2 = law.trial(g2, s2, duN, duS);
        const ContactForces& f3 = law.trial(g3, s3, duN, duS, 0.0);
        EXPECT_EQ(f2.Fn, f3.Fn);
        EXPECT_EQ(f2.Fs, f3.Fs);
        EXPECT_EQ(f3.Fs2, 0.0);
        EXPECT_EQ(f2.broken, f3.broken);
        broke = broke || f2.broken;
        law.commit(g2, s2);
        law.commit(g3, s3);
    }
    EXPECT_TRUE(broke);
    EXPECT_LT(s2.committed.Fn, 0.0);  // closed again after the break
}

TEST(Shear3D, CoulombConeReturnsRadially)
{
    // A broken contact under Fn = -1000 N: |Fs| <= tan(phi_res) 1000 N, the slip along the trial shear.
    ContactLaw law(brittle(false));
    const ContactGeometry g = geometry3d(1e-3, 1e-3);
    ContactState s;
    law.initState(s, 2);
    law.beginStep(0, 1);
    law.beginContactStep(g, s);
    const double kn = 30e9, ks = 0.3 * kn;
    law.trial(g, s, 10 * 4e6 * 1e-3 / kn, 0, 0);  // tension beyond f_t A: breaks
    ASSERT_TRUE(s.trial.broken);
    const double Fn = -1000, cap = std::tan(0.4) * 1000;
    const ContactForces& f = law.trial(g, s, Fn / kn, 3 * cap / ks, 4 * cap / ks);
    EXPECT_NEAR(f.Fn, Fn, 1e-9);
    EXPECT_NEAR(f.Fs, 0.6 * cap, 1e-9);
    EXPECT_NEAR(f.Fs2, 0.8 * cap, 1e-9);
    EXPECT_EQ(law.mode(s), ContactLaw::Mode::Sliding);
    const ContactForces& inside = law.trial(g, s, Fn / kn, 0.3 * cap / ks, -0.4 * cap / ks);
    EXPECT_NEAR(inside.Fs, 0.3 * cap, 1e-9);
    EXPECT_NEAR(inside.Fs2, -0.4 * cap, 1e-9);
    EXPECT_EQ(law.mode(s), ContactLaw::Mode::Sticking);
}

TEST(Shear3D, ShearStrengthSeesTheMagnitude)
{
    // c A + tan(phi) |Fn| against |(Fs, Fs2)|: each component at 0.75 of it is 1.06 of it together.
    ContactLaw law(brittle(true));
    const ContactGeometry g = geometry3d(1e-3, 1e-3);
    ContactState s;
    law.initState(s, 2);
    law.beginStep(0, 1);
    law.beginContactStep(g, s);
    const double kn = 30e9, ks = 0.3 * kn, Fn = -1000, cap = 8e6 * 1e-3 + std::tan(0.5) * 1000;
    law.trial(g, s, Fn / kn, 0.69 * cap / ks, 0.69 * cap / ks);  // |.| = 0.976 cap
    EXPECT_FALSE(s.trial.broken);
    EXPECT_NEAR(law.overload(g, s), std::hypot(0.69, 0.69), 1e-9);
    const ContactForces& f = law.trial(g, s, Fn / kn, 0.75 * cap / ks, 0.75 * cap / ks);
    EXPECT_TRUE(f.broken);
    EXPECT_EQ(f.mode, FailureMode::Shear);
    EXPECT_NEAR(std::hypot(f.Fs, f.Fs2), std::tan(0.4) * 1000, 1e-9);
}

TEST(Shear3D, TheHiddenStateHasABlockPerShearComponent)
{
    ContactLaw law(viscoelasticMortar());
    EXPECT_EQ(law.hiddenStateSize(1), 2 * law.chainSize());
    EXPECT_EQ(law.hiddenStateSize(2), 3 * law.chainSize());
    ContactState s;
    law.initState(s, 1);
    law.beginStep(1, 2);
    try {
        law.beginContactStep(geometry3d(1e-4, 1e-3), s);  // a 2D contact's state given a 3D geometry
        FAIL() << "a 2D state accepted for a 3D contact";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("hidden creep state size"), std::string::npos) << e.what();
    }
    ContactGeometry bad{1e-4, 1e-3};
    bad.shearComponents = 3;
    try {
        bad.validate();
        FAIL() << "shearComponents = 3 accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("shearComponents"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1 (2D) or 2 (3D)"), std::string::npos) << e.what();
    }
}
