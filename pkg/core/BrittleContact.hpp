// SPDX-License-Identifier: GPL-2.0-or-later
// Brittle contact strength (paper 2.4): tension cut-off Fn <= f_t A (tension positive), optional
// Mohr-Coulomb shear strength |Fs| <= c A + tan(phi) max(-Fn, 0); once broken the contact is a
// cohesionless Coulomb contact: Fn <= 0, |Fs| <= tan(phi_res) max(-Fn, 0).
// Pure functions on scalars; forces in N, areas in m2, stresses in Pa, angles in rad.
#pragma once

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
    /// Largest tensile normal force f_t A [N].
    static double maxTension(const BrittleStrength& s, double area);
    /// Shear capacity of an intact contact, c A + tan(phi) max(-Fn, 0) [N].
    static double shearCapacityIntact(const BrittleStrength& s, double area, double Fn);
    /// Shear capacity of a broken contact, tan(phi_res) max(-Fn, 0) [N].
    static double shearCapacityBroken(const BrittleStrength& s, double Fn);
    /// Whether an intact contact carrying (Fn, |Fs|) breaks, and how (tension checked first).
    static FailureMode check(const BrittleStrength& s, double area, double Fn, double shearMagnitude);
    /// Forces a broken contact transmits for unclamped trial forces (FnHat, FsTrial):
    /// Fn = min(FnHat, 0), Fs = FsTrial clamped to +-shearCapacityBroken(Fn).
    static void brokenForces(const BrittleStrength& s, double FnHat, double FsTrial, double& Fn, double& Fs);
};

}  // namespace swelldem::core
