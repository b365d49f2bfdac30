// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/ContactLaw.hpp"

#include "core/Validate.hpp"

#include <cmath>
#include <string>

namespace swelldem::core {

ContactLaw::ContactLaw(const ContactKindParams& p, double shortestLag, double longestLag) : p_(p)
{
    p_.validate();
    if (p_.behaviour != Behaviour::Elastic) b3_ = std::make_unique<B3Compliance>(p_.b3);
    if (p_.behaviour == Behaviour::Viscoelastic)
        creep_ = std::make_unique<SolidificationCreep>(p_.b3, shortestLag, longestLag, p_.chain, p_.interiorTime);
    if (p_.swelling)
        kinetics_ = std::make_unique<SwellingKinetics>(p_.tauC, p_.tauL, p_.referenceTemperature, p_.Uc, p_.UL);
    if (p_.temperatureDays.empty()) return;
    const TemperatureHistory history(p_.temperatureDays, p_.temperatures);
    if (kinetics_) swellingHistory_ = std::make_unique<SwellingHistory>(*kinetics_, history);
    if (b3_ && p_.thermal.on) clocks_ = std::make_unique<ThermalCreepClocks>(p_.thermal, history);
}

std::size_t ContactLaw::chainSize() const { return creep_ ? creep_->size() : 0; }

std::size_t ContactLaw::hiddenStateSize(int shearComponents) const { return (1 + std::size_t(shearComponents)) * chainSize(); }

void ContactLaw::initState(ContactState& s, int shearComponents) const
{
    s = ContactState{};
    s.gamma.assign(hiddenStateSize(shearComponents), 0.0);
}

void ContactLaw::beginStep(double tPrev, double t)
{
    if (p_.behaviour == Behaviour::Elastic) requireNonNegative("tPrev [day]", tPrev);
    else requirePositive("tPrev [day]", tPrev);
    requireGreaterEqual("t [day]", t, "tPrev", tPrev);
    tPrev_ = tPrev;
    t_ = t;
    stepTimes_ = clocks_ ? clocks_->step(tPrev, t) : StepTimes::identity(tPrev, t);
    switch (p_.behaviour) {
    case Behaviour::Elastic: stepModulus_ = p_.contactModulus; break;
    case Behaviour::AgingElastic:
        // the static modulus ages with hydration: E at the step's equivalent age
        stepModulus_ = b3_->E(SolidificationCreep::interiorTime(p_.interiorTime, stepTimes_.agePrev, stepTimes_.age));
        break;
    case Behaviour::Viscoelastic:
        creep_->factors(stepTimes_, factors_);
        stepModulus_ = factors_.Epp();
        break;
    }
    dxi_ = 0;
    if (!kinetics_) return;  // non-swelling kinds never evaluate the sigmoid
    ++swellingEvaluations_;
    dxi_ = swellingHistory_ ? swellingHistory_->increment(tPrev, t) : kinetics_->increment(tPrev, t);
}

double ContactLaw::swellingDisplacementInf(const ContactGeometry& g) const
{
    if (!p_.swelling) return 0;
    if (g.swellingDisplacementInf >= 0) return g.swellingDisplacementInf;
    return p_.swellingStrainInf > 0 ? p_.swellingStrainInf * g.length : p_.swellingDisplacementInf;
}

void ContactLaw::beginContactStep(const ContactGeometry& g, ContactState& s) const
{
    g.validate();
    const double A = g.area, L = g.length, alpha = p_.shearRatio;
    s.kn = stepModulus_ * A / L;
    s.ks = alpha * s.kn;
    s.duOffsetN = kinetics_ ? swellingDisplacementInf(g) * dxi_ * g.swellingFactor : 0.0;
    s.duOffsetN += g.imposedOpening - s.imposedOpeningRef;
    s.duOffsetS = s.duOffsetS2 = 0;
    const std::size_t hidden = hiddenStateSize(g.shearComponents);
    // A contact new to this law (created without one) starts with no creep history.
    if (s.gamma.empty()) s.gamma.assign(hidden, 0.0);
    if (creep_) {
        require(s.gamma.size() == hidden, "hidden creep state size of a contact", static_cast<double>(s.gamma.size()),
                std::to_string(hidden) + " (the kind's Kelvin chain changed while its contacts had a creep history)");
        const std::size_t n = chainSize();
        const double sigmaN = s.committed.Fn / A;
        const double sigmaS = s.committed.Fs / (alpha * A);
        s.duOffsetN += L * SolidificationCreep::inelasticStrainIncrement(factors_, sigmaN, s.gamma.data());
        s.duOffsetS += L * SolidificationCreep::inelasticStrainIncrement(factors_, sigmaS, s.gamma.data() + n);
        if (g.shearComponents == 2)
            s.duOffsetS2 += L * SolidificationCreep::inelasticStrainIncrement(factors_, s.committed.Fs2 / (alpha * A), s.gamma.data() + 2 * n);
    }
    s.trial = s.committed;
    s.shearStep = s.shearStep2 = 0;
}

const ContactForces& ContactLaw::trial(const ContactGeometry& g, ContactState& s, double duN, double duS, double duS2) const
{
    return settle(g, s, s.committed.FnHat + s.kn * (duN - s.duOffsetN), s.committed.Fs + s.ks * (duS - s.duOffsetS),
                  s.committed.Fs2 + s.ks * (duS2 - s.duOffsetS2), true);
}

ContactLaw::Mode ContactLaw::mode(const ContactState& s) const
{
    const ContactForces& tr = s.trial;
    if (!tr.broken) return Mode::Intact;
    if (!(tr.FnHat < 0)) return Mode::Open;
    const double cap = BrittleContact::shearCapacityBroken(p_.strength, tr.Fn);
    if (tr.Fs2 == 0) return std::abs(tr.Fs) < cap ? Mode::Sticking : Mode::Sliding;
    // A radial return lands on the cone to round-off, either side of it.
    return tr.shearMagnitude() < cap * (1 - 1e-12) ? Mode::Sticking : Mode::Sliding;
}

void ContactLaw::commit(const ContactGeometry& g, ContactState& s) const
{
    if (creep_) {
        const double A = g.area, alpha = p_.shearRatio;
        const double sN = s.committed.Fn / A, dsN = (s.trial.Fn - s.committed.Fn) / A;
        const double sS = s.committed.Fs / (alpha * A), dsS = (s.trial.Fs - s.committed.Fs) / (alpha * A);
        const std::size_t n = chainSize();
        SolidificationCreep::commit(factors_, sN, dsN, s.gamma.data());
        SolidificationCreep::commit(factors_, sS, dsS, s.gamma.data() + n);
        if (g.shearComponents == 2)
            SolidificationCreep::commit(factors_, s.committed.Fs2 / (alpha * A), (s.trial.Fs2 - s.committed.Fs2) / (alpha * A),
                                        s.gamma.data() + 2 * n);
    }
    s.committed = s.trial;
    s.openingRef = s.opening;
    s.imposedOpeningRef = g.imposedOpening;
}

}  // namespace swelldem::core
