// SPDX-License-Identifier: GPL-2.0-or-later
// Brittle contact strength (paper 2.4): tension cut-off Fn <= f_t A (tension positive), optional
// Mohr-Coulomb shear strength |Fs| <= c A + tan(phi) max(-Fn, 0); once broken the contact is a
// cohesionless Coulomb contact: Fn <= 0, |Fs| <= tan(phi_res) max(-Fn, 0).
// Pure functions on scalars (a shear of two components enters as its magnitude); forces in N, areas in m2, stresses in Pa, angles in rad.
#pragma once

#include <algorithm>
#include <cmath>

namespace swelldem::core {

enum class FailureMode { None, Tension, Shear };

/// Strength of one contact kind.
struct BrittleStrength {
    bool damage = false;          ///< false: never breaks (no check is made)
    double tensileStrength = 0;   ///< f_t [Pa], > 0 when damage
    bool shearFailure = false;    ///< Mohr-Coulomb shear failure of intact contacts (paper: off)
    double cohesion = 0;          ///< c [Pa], >= 0
    double frictionAngle = 0;     ///< phi of intact contacts [rad], 0 <= phi < pi/2
    double residualFrictionAngle = 0;  ///< phi_res of broken contacts [rad], 0 <= phi_res < pi/2
    void validate() const;
};

class BrittleContact {
public:
    // Inline: evaluated for every contact at every iteration.
    /// Largest tensile normal force f_t A [N].
    static double maxTension(const BrittleStrength& s, double area) { return s.tensileStrength * area; }
    /// Shear capacity of an intact contact, c A + tan(phi) max(-Fn, 0) [N].
    static double shearCapacityIntact(const BrittleStrength& s, double area, double Fn)
    {
        return s.cohesion * area + std::tan(s.frictionAngle) * std::max(-Fn, 0.0);
    }
    /// Shear capacity of a broken contact, tan(phi_res) max(-Fn, 0) [N].
    static double shearCapacityBroken(const BrittleStrength& s, double Fn)
    {
        return std::tan(s.residualFrictionAngle) * std::max(-Fn, 0.0);
    }
    /// How far an intact contact carrying (Fn, |Fs|) is beyond its strength: the larger of
    /// Fn / (f_t A) and, with shear failure on, |Fs| / (c A + tan(phi) max(-Fn, 0)); > 1 breaks it.
    static double overload(const BrittleStrength& s, double area, double Fn, double shearMagnitude)
    {
        if (!s.damage) return 0.0;
        double r = Fn / maxTension(s, area);
        if (s.shearFailure) {
            const double cap = shearCapacityIntact(s, area, Fn);
            r = std::max(r, cap > 0 ? std::fabs(shearMagnitude) / cap : (shearMagnitude != 0 ? HUGE_VAL : 0.0));
        }
        return r;
    }
    /// Whether an intact contact carrying (Fn, |Fs|) breaks, and how (tension checked first).
    static FailureMode check(const BrittleStrength& s, double area, double Fn, double shearMagnitude)
    {
        if (!s.damage) return FailureMode::None;
        if (Fn > maxTension(s, area)) return FailureMode::Tension;
        if (s.shearFailure && std::fabs(shearMagnitude) > shearCapacityIntact(s, area, Fn)) return FailureMode::Shear;
        return FailureMode::None;
    }
    /// Forces a broken contact transmits for unclamped trial forces (FnHat, FsTrial):
    /// Fn = min(FnHat, 0), Fs = FsTrial clamped to +-shearCapacityBroken(Fn).
    static void brokenForces(const BrittleStrength& s, double FnHat, double FsTrial, double& Fn, double& Fs)
    {
        Fn = std::min(FnHat, 0.0);
        const double cap = shearCapacityBroken(s, Fn);
        Fs = std::clamp(FsTrial, -cap, cap);
    }
    /// The same for a shear of two components (a 3D contact): a trial shear outside the Coulomb
    /// cone returns to it radially (the slip is along the trial shear). With FsTrial2 = 0 it is
    /// brokenForces above, to the bit.
    static void brokenForces(const BrittleStrength& s, double FnHat, double FsTrial, double FsTrial2, double& Fn, double& Fs,
                             double& Fs2)
    {
        if (FsTrial2 == 0) {
            brokenForces(s, FnHat, FsTrial, Fn, Fs);
            Fs2 = 0;
            return;
        }
        Fn = std::min(FnHat, 0.0);
        const double cap = shearCapacityBroken(s, Fn), m = std::hypot(FsTrial, FsTrial2);
        const double scale = m > cap ? cap / m : 1.0;
        Fs  = FsTrial * scale;
        Fs2 = FsTrial2 * scale;
    }
};

}  // namespace swelldem::core
