// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/ContactGeometry.hpp"

#include "core/Validate.hpp"

#include <cmath>

namespace swelldem::core {

void ContactGeometry::validate() const
{
    requirePositive("area [m2]", area);
    requirePositive("length [m]", length);
    requireNonNegative("swellingFactor [-]", swellingFactor);
    require(std::isfinite(imposedOpening), "imposedOpening [m]", imposedOpening, "a finite number");
    if (shearComponents != 1 && shearComponents != 2) require(false, "shearComponents", shearComponents, "1 (2D) or 2 (3D)");
}

}  // namespace swelldem::core
