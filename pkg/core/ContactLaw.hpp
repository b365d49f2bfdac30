// SPDX-License-Identifier: GPL-2.0-or-later
// Constitutive law of one contact kind, evaluated contact by contact (the YADE adapter and the
// tests use it the same way). One physical step [tPrev, t]:
//   law.beginStep(tPrev, t);                      // once per kind: shared factors, E(t*), dxi
//   for each contact: law.beginContactStep(g, s); // once per contact: kn'', ks'', offsets
//   equilibrium iterations: law.trial(g, s, duN, duS)   // displacement increments since step start
//   converged: for each contact law.commit(g, s);
// Convention: tension positive, opening displacement positive, kn = E A / L, ks = alpha kn;
// creep works in sigma = Fn/A, eps = u/L (normal) and sigma_s = Fs/(alpha A), eps_s = u_s/L (shear).
//   Fn = Fn_committed + kn'' (duN - du''_n - du_sw),  Fs = Fs_committed + ks'' (duS - du''_s).
// Shear is that of each tangent of the contact (ContactGeometry::shearComponents: one in 2D, two in
// 3D), creep acting on each component alike; strength and the Coulomb cone see its magnitude.
// "A scene pays only for what it uses": Elastic and AgingElastic kinds allocate no Kelvin state,
// non-swelling kinds never evaluate the sigmoid, damage off makes no strength check.
// Temperature (the kind's temperatureDays/temperatures): the swelling kinetics follow it through
// SwellingHistory, and the creep of aging kinds through ThermalCreepClocks when thermal.on; both
// are functions of the step's times alone, so a law rebuilt on a step (a reloaded scene) gives
// the same step bit for bit.
#pragma once

#include "core/ContactGeometry.hpp"
#include "core/ContactKindParams.hpp"
#include "core/ContactState.hpp"
#include "core/SolidificationCreep.hpp"
#include "core/SwellingKinetics.hpp"

#include <memory>
#include <vector>

namespace swelldem::core {

class ContactLaw {
public:
    /// shortestLag, longestLag [day]: the chain range of Viscoelastic kinds (shortest physical
    /// step, analysis span; see KelvinChain::forAnalysis). Ignored by the other kinds.
    explicit ContactLaw(const ContactKindParams& p, double shortestLag = 1e-2, double longestLag = 1e5);

    const ContactKindParams& params() const { return p_; }
    /// Doubles of hidden state per contact ((1 + shearComponents) x chain size for Viscoelastic, else 0).
    std::size_t hiddenStateSize(int shearComponents = 1) const;
    /// Kelvin units of the chain (0 unless Viscoelastic).
    std::size_t chainSize() const;
    /// The creep model (nullptr unless Viscoelastic).
    const SolidificationCreep* creep() const { return creep_.get(); }
    /// Resets a contact's state (forces zero, intact) and sizes its hidden array.
    void initState(ContactState& s, int shearComponents = 1) const;

    /// Per-kind step set-up; requires t >= tPrev, and tPrev > 0 for aging kinds [day].
    void beginStep(double tPrev, double t);
    double stepStart() const { return tPrev_; }
    double stepEnd() const { return t_; }
    /// Modulus of the step: E_c, E(t*) or the incremental E'' [Pa].
    double stepModulus() const { return stepModulus_; }
    /// Swelling ratio increment xi(t) - xi(tPrev) of the step (0 for non-swelling kinds).
    double swellingIncrement() const { return dxi_; }
    /// Step factors of a Viscoelastic kind (valid after beginStep), else nullptr.
    const StepFactors* stepFactors() const { return creep_ ? &factors_ : nullptr; }
    /// The step's times as creep sees them (the physical ones unless creep follows a temperature history).
    const StepTimes& stepTimes() const { return stepTimes_; }
    /// How many times the sigmoid/ODE was evaluated (for the "pays for what it uses" tests).
    long swellingEvaluations() const { return swellingEvaluations_; }

    /// Ultimate swelling displacement of a contact [m].
    double swellingDisplacementInf(const ContactGeometry& g) const;

    /// Per-contact step set-up (after beginStep): stiffnesses and constant offsets; trial := committed.
    /// A state without hidden variables (a new contact) gets them, zero.
    void beginContactStep(const ContactGeometry& g, ContactState& s) const;
    /// Trial forces for displacement increments since the step start [m]; strength checks;
    /// a break is kept for the rest of the step. Returns s.trial.
    const ContactForces& trial(const ContactGeometry& g, ContactState& s, double duN, double duS, double duS2 = 0) const;
    /// The path of a solver that carries the shear force itself (YADE's rotated incremental shear
    /// vector): normal opening u [m] (the step's increment is u - s.openingRef, kept in s.opening) and
    /// trial shear force FsTrial [N]. An intact contact breaks here only when breakNow (else see
    /// breakIfOverloaded). Returns s.trial.
    const ContactForces& update(const ContactGeometry& g, ContactState& s, double opening, double FsTrial,
                                bool breakNow) const
    {
        return update(g, s, opening, FsTrial, 0.0, breakNow);
    }
    /// The same with the trial shear's two components (a 3D contact).
    const ContactForces& update(const ContactGeometry& g, ContactState& s, double opening, double FsTrial, double FsTrial2,
                                bool breakNow) const;
    /// The same, for a solver that gives the shear as a displacement increment dShear [m] of the
    /// iteration: the trial shear force is taken from the step's start, Fs = committed.Fs +
    /// ks'' (shearStep - du''_s), so that a broken contact's slip is decided by the state reached,
    /// not by the path of the iterations (the return mapping of implicit codes); slip becomes
    /// permanent at commit.
    const ContactForces& updateFromStepStart(const ContactGeometry& g, ContactState& s, double opening, double dShear,
                                             bool breakNow) const
    {
        return updateFromStepStart(g, s, opening, dShear, 0.0, breakNow);
    }
    /// The same with the iteration's shear along both tangents (a 3D contact).
    const ContactForces& updateFromStepStart(const ContactGeometry& g, ContactState& s, double opening, double dShear,
                                             double dShear2, bool breakNow) const;
    /// At equilibrium: breaks an intact contact of a damaging kind whose trial forces exceed its
    /// strength; returns whether it broke. Its forces follow at the next update.
    bool breakIfOverloaded(const ContactGeometry& g, ContactState& s) const;
    /// BrittleContact::overload of the trial forces of an intact contact (0 once broken) [-].
    double overload(const ContactGeometry& g, const ContactState& s) const
    {
        return s.trial.broken ? 0.0 : BrittleContact::overload(p_.strength, g.area, s.trial.FnHat, s.trial.shearMagnitude());
    }
    /// The state that decides a contact's tangent stiffness in an implicit solver: kn'', ks'' while
    /// intact or sticking, kn'' alone while sliding (its shear force stays on the Coulomb cone),
    /// none while open (FnHat >= 0).
    enum class Mode { Intact, Open, Sticking, Sliding };
    Mode mode(const ContactState& s) const;
    /// Converged step: updates the hidden strains from the transmitted force increments and
    /// copies trial into committed.
    void commit(const ContactGeometry& g, ContactState& s) const;

private:
    const ContactForces& settle(const ContactGeometry& g, ContactState& s, double FnHat, double FsTrial, double FsTrial2,
                                bool breakNow) const;
    ContactKindParams p_;
    std::unique_ptr<SolidificationCreep> creep_;
    std::unique_ptr<B3Compliance> b3_;
    std::unique_ptr<SwellingKinetics> kinetics_;
    std::unique_ptr<SwellingHistory> swellingHistory_;  // kinetics under a temperature history
    std::unique_ptr<ThermalCreepClocks> clocks_;        // creep under a temperature history
    StepFactors factors_;
    StepTimes stepTimes_;
    double tPrev_ = 0, t_ = 0, stepModulus_ = 0, dxi_ = 0;
    long swellingEvaluations_ = 0;
};


// Inline: the YADE law calls these for every contact at every iteration.
inline const ContactForces& ContactLaw::settle(const ContactGeometry& g, ContactState& s, double FnHat, double FsTrial,
                                               double FsTrial2, bool breakNow) const
{
    ContactForces& tr = s.trial;
    tr.FnHat = FnHat;
    if (!tr.broken) {
        tr.Fn  = FnHat;
        tr.Fs  = FsTrial;
        tr.Fs2 = FsTrial2;
        if (!breakNow || !breakIfOverloaded(g, s)) return tr;
    }
    BrittleContact::brokenForces(p_.strength, FnHat, FsTrial, FsTrial2, tr.Fn, tr.Fs, tr.Fs2);
    return tr;
}

inline bool ContactLaw::breakIfOverloaded(const ContactGeometry& g, ContactState& s) const
{
    ContactForces& tr = s.trial;
    if (tr.broken) return false;
    const FailureMode m = BrittleContact::check(p_.strength, g.area, tr.FnHat, tr.shearMagnitude());
    if (m == FailureMode::None) return false;
    tr.broken = true;
    tr.mode = m;
    return true;
}

inline const ContactForces& ContactLaw::update(const ContactGeometry& g, ContactState& s, double opening, double FsTrial,
                                               double FsTrial2, bool breakNow) const
{
    s.opening = opening;
    return settle(g, s, s.committed.FnHat + s.kn * ((opening - s.openingRef) - s.duOffsetN), FsTrial, FsTrial2, breakNow);
}

inline const ContactForces& ContactLaw::updateFromStepStart(const ContactGeometry& g, ContactState& s, double opening,
                                                            double dShear, double dShear2, bool breakNow) const
{
    s.opening = opening;
    s.shearStep += dShear;
    s.shearStep2 += dShear2;
    return settle(g, s, s.committed.FnHat + s.kn * ((opening - s.openingRef) - s.duOffsetN),
                  s.committed.Fs + s.ks * (s.shearStep - s.duOffsetS), s.committed.Fs2 + s.ks * (s.shearStep2 - s.duOffsetS2),
                  breakNow);
}

}  // namespace swelldem::core
