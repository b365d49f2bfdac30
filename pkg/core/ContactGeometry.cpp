// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/ContactGeometry.hpp"

#include "core/Validate.hpp"

namespace swelldem::core {

void ContactGeometry::validate() const
{
    requirePositive("area [m2]", area);
    requirePositive("length [m]", length);
    if (shearComponents != 1 && shearComponents != 2) require(false, "shearComponents", shearComponents, "1 (2D) or 2 (3D)");
}

}  // namespace swelldem::core
