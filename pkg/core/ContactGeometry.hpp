// SPDX-License-Identifier: GPL-2.0-or-later
// Geometry of one contact as the constitutive law needs it.
#pragma once

namespace swelldem::core {

struct ContactGeometry {
    double area = 0;    ///< facet area A_c [m2] (2D: facet length x out-of-plane thickness b; 3D: the power-diagram facet's area), > 0
    double length = 0;  ///< centre distance L [m], > 0
    /// Per-contact ultimate swelling displacement d_inf [m] overriding the kind's (< 0: the kind's).
    /// Lets a chosen share of a kind's contacts swell (the paper's ASR gel pockets).
    double swellingDisplacementInf = -1;
    /// Factor on this step's swelling increment, d_inf f dxi (a moisture driver's f(h); 1 when
    /// the reaction has all the water it needs): gel formed in earlier steps stays [-], >= 0.
    double swellingFactor = 1;
    /// Imposed free normal opening (drying shrinkage < 0) in force at the end of the current
    /// step, a total since the contact was made; the step imposes its change from the last
    /// committed value (ContactState::imposedOpeningRef) [m].
    double imposedOpening = 0;
    /// Tangents of the contact plane that carry shear: 1 in a 2D section (the in-plane tangent),
    /// 2 for a 3D contact (two orthogonal tangents of its facet).
    int shearComponents = 1;
    void validate() const;
};

}  // namespace swelldem::core
