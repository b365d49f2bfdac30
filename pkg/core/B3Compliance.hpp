// SPDX-License-Identifier: GPL-2.0-or-later
// B3 basic-creep compliance (Bazant & Baweja 1995) with Bazant's approximation of Q(t,t').
// Units: times in days, compliances in 1/Pa (the paper's 1e-6/MPa = 1e-12/Pa), moduli in Pa.
#pragma once

namespace swelldem::core {

/// B3 basic-creep parameters of one material.
struct B3Params {
    double q1 = 0;            ///< instantaneous compliance [1/Pa], > 0
    double q2 = 0;            ///< aging viscoelastic compliance [1/Pa], > 0
    double q3 = 0;            ///< non-aging viscoelastic compliance [1/Pa], >= 0
    double q4 = 0;            ///< flow compliance [1/Pa], >= 0
    double n = 0.1;           ///< exponent of the micro-compliance, 0 < n < 1
    double m = 0.5;           ///< exponent of the solidified volume 1/v(t), 0 < m < 1
    double lambda0 = 1.0;     ///< time unit of the law [day], > 0
    double elasticLag = 0.01; ///< load duration defining the static modulus E(t) [day], > 0

    /// Throws std::invalid_argument naming the first parameter out of range.
    void validate() const;
    /// Table 3.3 of the paper (converted to 1/Pa).
    static B3Params mortarM6();
    static B3Params concreteC4();
    static B3Params itz();
};

/// J(t,t') = q1 + q2 Q(t,t') + q3 ln(1 + ((t-t')/lambda0)^n) + q4 ln(t/t').
/// Q is Bazant's closed-form approximation, whose coefficients were fitted for
/// n = 0.1, m = 0.5, lambda0 = 1 day (times enter as t/lambda0).
class B3Compliance {
public:
    explicit B3Compliance(const B3Params& p);  ///< validates p

    const B3Params& params() const { return p_; }

    /// Creep compliance [1/Pa]; requires t > t' > 0 [day].
    double J(double t, double tPrime) const;
    /// Bazant's approximation of the solidification integral Q(t,t') [-]; t > t' > 0.
    double Q(double t, double tPrime) const;
    /// Static (elastic) modulus E(t) = 1 / J(t + elasticLag, t) [Pa]; t > 0.
    double E(double t) const;
    /// Inverse solidified volume 1/v(t) = (lambda0/t)^m + q3/q2 [-]; t > 0.
    double invV(double t) const;
    /// Non-aging micro-compliance Phi(xi) = q2 ln(1 + (xi/lambda0)^n) [1/Pa]; xi >= 0.
    double phi(double xi) const;

private:
    B3Params p_;
};

}  // namespace swelldem::core
