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
    /// Tangents of the contact plane that carry shear: 1 in a 2D section (the in-plane tangent),
    /// 2 for a 3D contact (two orthogonal tangents of its facet).
    int shearComponents = 1;
    void validate() const;
};

}  // namespace swelldem::core
