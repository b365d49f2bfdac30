// SPDX-License-Identifier: GPL-2.0-or-later
// Per-contact state: a committed part (converged at the end of the last physical step) and a trial
// part that the equilibrium iterations of the current step overwrite, plus the step's constant
// incremental data set by ContactLaw::beginContactStep. It is all a solver needs from a contact for
// a step: within the step an intact contact is linear, Fn = committed.FnHat + kn (duN - duOffsetN),
// Fs = committed.Fs + ks (duS - duOffsetS) (ContactLaw::tangent gives a broken one's tangent).
#pragma once

#include "core/BrittleContact.hpp"

#include <vector>

namespace swelldem::core {

/// Forces of one contact (tension positive; shear signed along the 2D tangent) [N].
struct ContactForces {
    double Fn = 0;       ///< transmitted normal force [N]
    double Fs = 0;       ///< transmitted shear force [N]
    double FnHat = 0;    ///< unclamped incremental normal force [N] (= Fn while intact; > 0 on a
                         ///< broken contact is the crack opening times the stiffness)
    bool broken = false;
    FailureMode mode = FailureMode::None;  ///< how it broke
};

struct ContactState {
    ContactForces committed;
    ContactForces trial;
    /// Hidden Kelvin strains, normal units then shear units; empty unless the kind is Viscoelastic.
    std::vector<double> gamma;
    // step data, constant during the step's equilibrium iterations:
    double kn = 0;          ///< incremental normal stiffness kn'' of the step [N/m]
    double ks = 0;          ///< incremental shear stiffness ks'' [N/m]
    double duOffsetN = 0;   ///< inelastic + swelling normal displacement increment [m] (opening > 0)
    double duOffsetS = 0;   ///< inelastic shear displacement increment [m]
    // normal opening (centre distance minus the radii; the caller's measure) [m]:
    double openingRef = 0;  ///< at the end of the last converged step (at creation: stress-free)
    double opening = 0;     ///< in the current trial
    double shearStep = 0;   ///< relative tangential displacement since the step's start [m] (ContactLaw::updateFromStepStart)

    double* gammaNormal() { return gamma.data(); }
    double* gammaShear() { return gamma.data() + gamma.size() / 2; }
    const double* gammaNormal() const { return gamma.data(); }
    const double* gammaShear() const { return gamma.data() + gamma.size() / 2; }
};

}  // namespace swelldem::core
