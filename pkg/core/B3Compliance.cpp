// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/B3Compliance.hpp"

#include "core/Validate.hpp"

#include <cmath>

namespace swelldem::core {

void B3Params::validate() const
{
    requirePositive("q1 [1/Pa]", q1);
    requirePositive("q2 [1/Pa]", q2);
    requireNonNegative("q3 [1/Pa]", q3);
    requireNonNegative("q4 [1/Pa]", q4);
    requireOpenInterval("n", n, 0.0, 1.0);
    requireOpenInterval("m", m, 0.0, 1.0);
    requirePositive("lambda0 [day]", lambda0);
    requirePositive("elasticLag [day]", elasticLag);
}

namespace {
B3Params fromTable(double q1, double q2, double q3, double q4)
{
    // table values in 1e-6/MPa = 1e-12/Pa
    B3Params p;
    p.q1 = q1 * 1e-12;
    p.q2 = q2 * 1e-12;
    p.q3 = q3 * 1e-12;
    p.q4 = q4 * 1e-12;
    return p;
}
}  // namespace

B3Params B3Params::mortarM6() { return fromTable(6.7, 108.1, 44.2, 14.3); }
B3Params B3Params::concreteC4() { return fromTable(9.0, 23.7, 46.6, 5.1); }
B3Params B3Params::itz() { return fromTable(19.3, 194.6, 72.9, 7.5); }

B3Compliance::B3Compliance(const B3Params& p) : p_(p) { p_.validate(); }

double B3Compliance::Q(double t, double tPrime) const
{
    requirePositive("t' [day]", tPrime);
    requireGreater("t [day]", t, "t'", tPrime);
    const double tp = tPrime / p_.lambda0;
    const double Qf = 1.0 / (0.086 * std::pow(tp, 2.0 / 9.0) + 1.21 * std::pow(tp, 4.0 / 9.0));
    const double Z = std::pow(tp, -p_.m) * std::log1p(std::pow((t - tPrime) / p_.lambda0, p_.n));
    const double r = 1.7 * std::pow(tp, 0.12) + 8.0;
    // Q = Qf (1 + (Qf/Z)^r)^(-1/r), written so that (ratio)^r never overflows
    if (Z >= Qf) return Qf * std::pow(1.0 + std::pow(Qf / Z, r), -1.0 / r);
    return Z * std::pow(1.0 + std::pow(Z / Qf, r), -1.0 / r);
}

double B3Compliance::J(double t, double tPrime) const
{
    const double q = Q(t, tPrime);  // validates t, t'
    return p_.q1 + p_.q2 * q + p_.q3 * std::log1p(std::pow((t - tPrime) / p_.lambda0, p_.n)) +
           p_.q4 * std::log1p((t - tPrime) / tPrime);
}

double B3Compliance::E(double t) const
{
    requirePositive("t [day]", t);
    return 1.0 / J(t + p_.elasticLag, t);
}

double B3Compliance::invV(double t) const
{
    requirePositive("t [day]", t);
    return std::pow(p_.lambda0 / t, p_.m) + p_.q3 / p_.q2;
}

double B3Compliance::phi(double xi) const
{
    requireNonNegative("xi [day]", xi);
    return p_.q2 * std::log1p(std::pow(xi / p_.lambda0, p_.n));
}

}  // namespace swelldem::core
