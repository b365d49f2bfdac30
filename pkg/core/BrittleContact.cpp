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

double BrittleContact::maxTension(const BrittleStrength& s, double area) { return s.tensileStrength * area; }

double BrittleContact::shearCapacityIntact(const BrittleStrength& s, double area, double Fn)
{
    return s.cohesion * area + std::tan(s.frictionAngle) * std::max(-Fn, 0.0);
}

double BrittleContact::shearCapacityBroken(const BrittleStrength& s, double Fn)
{
    return std::tan(s.residualFrictionAngle) * std::max(-Fn, 0.0);
}

FailureMode BrittleContact::check(const BrittleStrength& s, double area, double Fn, double shearMagnitude)
{
    if (!s.damage) return FailureMode::None;
    if (Fn > maxTension(s, area)) return FailureMode::Tension;
    if (s.shearFailure && std::fabs(shearMagnitude) > shearCapacityIntact(s, area, Fn)) return FailureMode::Shear;
    return FailureMode::None;
}

void BrittleContact::brokenForces(const BrittleStrength& s, double FnHat, double FsTrial, double& Fn, double& Fs)
{
    Fn = std::min(FnHat, 0.0);
    const double cap = shearCapacityBroken(s, Fn);
    Fs = std::clamp(FsTrial, -cap, cap);
}

}  // namespace swelldem::core
