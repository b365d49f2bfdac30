// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/BrittleContact.hpp"

#include "core/Validate.hpp"

#include <algorithm>
#include <cmath>

namespace swelldem::core {

void BrittleStrength::validate() const
{
    const double halfPi = std::acos(0.0);
    if (damage) requirePositive("tensileStrength f_t [Pa]", tensileStrength);
    requireNonNegative("cohesion c [Pa]", cohesion);
    require(frictionAngle >= 0 && frictionAngle < halfPi, "frictionAngle phi [rad]", frictionAngle,
            "0 <= phi < pi/2");
    require(residualFrictionAngle >= 0 && residualFrictionAngle < halfPi, "residualFrictionAngle [rad]",
            residualFrictionAngle, "0 <= phi_res < pi/2");
}

}  // namespace swelldem::core
