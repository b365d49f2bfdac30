// SPDX-License-Identifier: GPL-2.0-or-later
// Per-contact state: a committed part (converged at the end of the last physical step) and a trial
// part that the equilibrium iterations of the current step overwrite, plus the step's constant
// incremental data set by ContactLaw::beginContactStep. It is all a solver needs from a contact for
// a step: within the step an intact contact is linear, Fn = committed.FnHat + kn (duN - duOffsetN),
// Fs = committed.Fs + ks (duS - duOffsetS) (ContactLaw::tangent gives a broken one's tangent).
// Shear has one component in a 2D section (along the in-plane tangent) and two on a 3D contact
// (along two orthogonal tangents of the facet, chosen by the caller); the second is 0 in 2D, where
// the arithmetic of the first is the one of a scalar shear.
#include <cmath>
#pragma once

#include "core/BrittleContact.hpp"

#include <vector>

namespace swelldem::core {

/// Forces of one contact (tension positive; shear signed along the contact's tangents) [N].
struct ContactForces {
    double Fn = 0;       ///< transmitted normal force [N]
    double Fs = 0;       ///< transmitted shear force along the first tangent [N]
    double Fs2 = 0;      ///< transmitted shear force along the second tangent (3D; 0 in 2D) [N]
    double FnHat = 0;    ///< unclamped incremental normal force [N] (= Fn while intact; > 0 on a
                         ///< broken contact is the crack opening times the stiffness)
    bool broken = false;
    FailureMode mode = FailureMode::None;  ///< how it broke
    /// |(Fs, Fs2)|: |Fs| exactly when Fs2 = 0 (2D) [N].
    double shearMagnitude() const { return Fs2 == 0 ? std::fabs(Fs) : std::hypot(Fs, Fs2); }
};

struct ContactState {
    ContactForces committed;
    ContactForces trial;
    /// Hidden Kelvin strains, a block of the chain's units for the normal direction then one per shear
    /// component (ContactGeometry::shearComponents); empty unless the kind is Viscoelastic.
    std::vector<double> gamma;
    // step data, constant during the step's equilibrium iterations:
    double kn = 0;          ///< incremental normal stiffness kn'' of the step [N/m]
    double ks = 0;          ///< incremental shear stiffness ks'' [N/m]
    double duOffsetN = 0;   ///< inelastic + swelling normal displacement increment [m] (opening > 0)
    double duOffsetS = 0;   ///< inelastic shear displacement increment along the first tangent [m]
    double duOffsetS2 = 0;  ///< the same along the second tangent (3D) [m]
    // normal opening (centre distance minus the radii; the caller's measure) [m]:
    double openingRef = 0;  ///< at the end of the last converged step (at creation: stress-free)
    double opening = 0;     ///< in the current trial
    double shearStep = 0;   ///< relative tangential displacement since the step's start [m] (ContactLaw::updateFromStepStart)
    double shearStep2 = 0;  ///< the same along the second tangent (3D) [m]
    double imposedOpeningRef = 0;  ///< ContactGeometry::imposedOpening at the last commit [m]
};

}  // namespace swelldem::core
