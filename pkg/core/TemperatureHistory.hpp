// SPDX-License-Identifier: GPL-2.0-or-later
// A temperature history T(t) of one contact kind: piecewise linear through (days[i], T[i]), held at
// the first value before the first day and at the last after the last one. Times in days (the
// concrete's age, the clock of the swelling kinetics and of creep), temperatures in K.
//
// ArrheniusTime is the time a thermally activated process sees under that history,
//   t_U(t) = integral_0^t exp[U (1/T0 - 1/T(s))] ds,
// the equivalent time of the rate-process theory (t_U = t at T0; t_U = beta t at a constant T).
// It is a function of t alone, computed the same way whatever the order of the calls, so that a
// run saved and reloaded continues bit-identically.
#pragma once

#include <cstddef>
#include <vector>

namespace swelldem::core {

class TemperatureHistory {
public:
    static constexpr double kMaxTemperature = 373.15;  ///< upper bound of a temperature [K] (100 C)

    /// No history (empty()).
    TemperatureHistory() = default;
    /// Validates (see validate) and keeps the table.
    TemperatureHistory(std::vector<double> days, std::vector<double> temperatures);
    /// Both empty (no history), or the same length with days >= 0 strictly increasing and
    /// 0 < T <= 373.15 K; throws std::invalid_argument naming the entry (temperatureDays[i],
    /// temperatures[i]) and its allowed range.
    static void validate(const std::vector<double>& days, const std::vector<double>& temperatures);

    bool empty() const { return days_.empty(); }
    /// The same temperature at every time (one entry, or all entries equal).
    bool isConstant() const { return constant_; }
    const std::vector<double>& days() const { return days_; }
    const std::vector<double>& temperatures() const { return temps_; }
    /// T(t) [K]; the history must not be empty.
    double at(double t) const;
    /// Index j of the linear piece holding t: days[j] <= t < days[j+1], or -1 before the first day
    /// and size()-1 from the last day on.
    std::ptrdiff_t segment(double t) const;

private:
    std::vector<double> days_, temps_;
    bool constant_ = true;
};

class ArrheniusTime {
public:
    /// U: activation energy over the gas constant [K], >= 0; T0: the temperature at which the
    /// process runs at its nominal rate [K], > 0. An empty history runs at T0 throughout.
    ArrheniusTime(const TemperatureHistory& history, double U, double T0);

    /// Rate factor beta(T) = exp[U (1/T0 - 1/T)] [-].
    double factor(double T) const;
    /// Integral of beta(T(s)) over [t1, t2] [day]; 0 <= t1 <= t2. Exact (beta x duration) where T
    /// is constant; over a linear piece 8-point Gauss-Legendre on panels of at most 5 K (measured
    /// against Simpson's rule in long double: 4.7e-15 relative for U = 9400 K, tests/core/test_Temperature.cpp).
    double integral(double t1, double t2) const;
    /// t_U(t) = integral over [0, t] [day].
    double at(double t) const;

private:
    double piece(double a, double b) const;  // a, b within one linear piece of the history
    TemperatureHistory h_;
    double U_, T0_;
    std::vector<double> cumulative_;  // at(days[j])
};

}  // namespace swelldem::core
