// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/ContactGeometry.hpp"

#include "core/Validate.hpp"

namespace swelldem::core {

void ContactGeometry::validate() const
{
    requirePositive("area [m2]", area);
    requirePositive("length [m]", length);
}

}  // namespace swelldem::core
