// SPDX-License-Identifier: GPL-2.0-or-later
// Larive's swelling kinetics (paper eqs. 5-9), free swelling ratio xi in [0, 1]:
//   ODE     t_c(T, xi) dxi/dt + xi = 1,  t_c = tau_c (1 + e^(-tau_L/tau_c)) / (xi + e^(-tau_L/tau_c)),
//   closed  xi(t) = (1 - e^(-t/tau_c)) / (1 + e^(-(t - tau_L)/tau_c))   (constant T, xi(0) = 0),
//   Arrhenius (Larive 1998; Ulm et al. 2000):
//           tau(T) = tau(T0) exp[U (1/T - 1/T0)],  U_c = 5400 K, U_L = 9400 K.
// Times in days, temperatures in K. tau_c, tau_L are the values at the reference temperature T0.
#pragma once

#include "core/TemperatureHistory.hpp"

#include <cstddef>
#include <functional>
#include <vector>

namespace swelldem::core {

class SwellingKinetics {
public:
    static constexpr double kUc = 5400.0;   ///< activation energy / R of tau_c [K]
    static constexpr double kUL = 9400.0;   ///< activation energy / R of tau_L [K]
    static constexpr double kT0 = 293.15;   ///< default reference temperature [K] (20 C)
    static constexpr double kMaxLatencyRatio = 700.0;  ///< tau_L/tau_c above it e^(-ratio) underflows

    /// tauC > 0, 0 <= tauL <= 700 tauC [day]; T0 > 0, Uc, UL >= 0 [K].
    SwellingKinetics(double tauC, double tauL, double T0 = kT0, double Uc = kUc, double UL = kUL);

    double tauC() const { return tauC_; }
    double tauL() const { return tauL_; }
    double T0() const { return T0_; }
    /// Arrhenius-scaled characteristic and latency times at temperature T [K] -> [day].
    double tauC(double T) const;
    double tauL(double T) const;

    /// Closed form at the reference temperature; t >= 0 [day].
    double xi(double t) const;
    /// Closed form at constant temperature T [K] (history from t = 0 at T).
    double xiAt(double t, double T) const;
    /// xi(t2) - xi(t1) at T0 without cancellation for tiny steps; 0 <= t1 <= t2.
    double increment(double t1, double t2) const;
    /// Same at constant temperature T [K].
    double incrementAt(double t1, double t2, double T) const;

    /// Right-hand side of the ODE: dxi/dt = (1 - xi) / t_c(T, xi) [1/day].
    double rate(double xi, double T) const;
    /// Integrates the ODE from (t0, xi0) to t1 under the temperature history T(t) [K]: substeps
    /// with T frozen at each substep's mid-point, solved exactly there (the ODE at constant T is
    /// a logistic equation: (xi + c)/(1 - xi) grows like e^(t/tau_c)). substeps <= 0 chooses
    /// ceil(20 (t1 - t0) / tau_c(T0)) (at least 1, at most 1e6).
    double integrate(double xi0, double t0, double t1, const std::function<double(double)>& T,
                     int substeps = 0) const;
    /// Same with a piecewise-linear history (TemperatureHistory: days increasing, temperatures
    /// [K], held constant outside the table).
    double integrate(double xi0, double t0, double t1, const std::vector<double>& times,
                     const std::vector<double>& temperatures, int substeps = 0) const;
    /// The exact solution of the ODE over a duration h [day] at the constant temperature T [K],
    /// from xi: (xi + c)/(1 - xi) grows by e^(h/tau_c(T)), c = e^(-tau_L(T)/tau_c(T)).
    double advance(double xi, double h, double T) const;

private:
    static double logistic(double z);
    double xiClosed(double t, double tc, double tl) const;
    double incrementClosed(double t1, double t2, double tc, double tl) const;
    double tauC_, tauL_, T0_, Uc_, UL_;
};

/// Larive's xi(t) under a temperature history, as a function of t alone: the same value whatever
/// the order of the calls (a reloaded run continues bit-identically).
///  * constant history: the closed form at that temperature (increment without cancellation);
///  * varying history: the ODE integrated on a fixed grid of substeps from t = 0, each solved
///    exactly at the temperature of its mid-point (SwellingKinetics::advance): every linear piece
///    of the history is cut into substeps of at most kSubstepKelvin, constant pieces into one;
///    xi(t) continues from the last grid node before t. The grid's last node reached is cached.
class SwellingHistory {
public:
    /// Largest temperature change over one substep [K]; the midpoint rule's error is of second
    /// order in it (tests/core/test_Temperature.cpp measures it against an RK4 of the ODE).
    static constexpr double kSubstepKelvin = 0.1;

    /// The history must not be empty.
    SwellingHistory(const SwellingKinetics& kinetics, const TemperatureHistory& history);
    /// xi(t), t >= 0 [day].
    double xi(double t);
    /// xi(t2) - xi(t1), 0 <= t1 <= t2 [day].
    double increment(double t1, double t2);

private:
    SwellingKinetics k_;
    TemperatureHistory h_;
    std::vector<double> nodes_;  // 0, then the substep ends up to the last day of the history
    std::size_t node_ = 0;       // last node reached
    double xiNode_ = 0;          // xi there
};

}  // namespace swelldem::core
