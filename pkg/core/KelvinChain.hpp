// SPDX-License-Identifier: GPL-2.0-or-later
// Dirichlet-series (Kelvin chain) expansion of the non-aging micro-compliance of B3's
// solidification theory,
//     Phi(xi) = q2 ln(1 + (xi/lambda0)^n)  ~=  A0 + sum_mu A_mu (1 - exp(-xi/tau_mu)),
// with A_mu taken from the continuous retardation spectrum L(tau) of Phi (Post-Widder
// inversion of order k, Bazant & Xi 1995, by default Richardson-extrapolated over the orders
// k and 2k: L = 2 L_2k - L_k): A_mu = L(tau_mu) * (width of the unit's cell in ln tau), and
// A0 = integral of L over ln tau below the first cell (closed form).
// Units: times in days, compliances in 1/Pa.
#pragma once

#include <cstddef>
#include <vector>

namespace swelldem::core {

/// How a chain is built (its size is a cost/accuracy knob: see docs/physics-core.md).
struct KelvinChainOptions {
    double unitsPerDecade = 1.0;  ///< density of retardation times [units per decade], 0.1..20
    int order = 2;                ///< Post-Widder order k, 1..4 (1..8 without Richardson)
    bool richardson = true;       ///< use 2 L_2k - L_k instead of L_k
    double marginBelow = 1.0;     ///< forAnalysis: tau_1 <= shortestLag / 10^marginBelow [decades]
    double marginAbove = 2.0;     ///< forAnalysis: tau_N >= longestLag * 10^marginAbove [decades] (ContactKind.kelvinMarginAbove)
    void validate() const;
};

class KelvinChain {
public:
    /// Chain with the given retardation times [day] (strictly increasing, > 0).
    /// Cell of unit mu in ln tau: from the log-midpoint with its lower neighbour to the one with
    /// its upper neighbour (end cells symmetric; a single unit gets one decade).
    KelvinChain(double q2, double n, double lambda0, std::vector<double> tau,
                const KelvinChainOptions& opt = {});

    /// Units on the grid tau_j = lambda0 * 10^(j / unitsPerDecade) covering [tauMin, tauMax]:
    /// first unit at or below tauMin, last at or above tauMax.
    static KelvinChain forRange(double q2, double n, double lambda0, double tauMin, double tauMax,
                                const KelvinChainOptions& opt = {});

    /// Range chosen from the analysis: shortestLag = shortest load duration to resolve (the
    /// shortest physical step, or the first creep lag of interest), longestLag = the analysis'
    /// total span (t_end - t_start) [day]; tau_1 <= shortestLag / 10^marginBelow,
    /// tau_N >= longestLag * 10^marginAbove.
    static KelvinChain forAnalysis(double q2, double n, double lambda0, double shortestLag,
                                   double longestLag, const KelvinChainOptions& opt = {});

    std::size_t size() const { return tau_.size(); }  ///< number of Kelvin units (without A0)
    const std::vector<double>& tau() const { return tau_; }  ///< retardation times [day]
    const std::vector<double>& A() const { return A_; }      ///< unit compliances [1/Pa]
    double A0() const { return A0_; }                        ///< zero-time spring [1/Pa]
    const KelvinChainOptions& options() const { return opt_; }

    /// The chain's compliance A0 + sum A_mu (1 - exp(-xi/tau_mu)) [1/Pa]; xi >= 0 [day].
    double compliance(double xi) const;
    /// The function it expands, q2 ln(1 + (xi/lambda0)^n) [1/Pa].
    double phi(double xi) const;

    /// Post-Widder retardation spectrum of order k of Phi, L_k(tau) [1/Pa per unit ln tau]:
    /// L_k(tau) = -(-k tau)^k / (k-1)! * Phi^(k)(k tau); with richardson: 2 L_2k - L_k.
    static double spectrum(double tau, double q2, double n, double lambda0, int order,
                           bool richardson = false);
    /// Integral of the same spectrum over ln tau from 0 to tau (closed form) [1/Pa].
    static double spectrumIntegralBelow(double tau, double q2, double n, double lambda0, int order,
                                        bool richardson = false);

private:
    double q2_, n_, lambda0_;
    KelvinChainOptions opt_;
    std::vector<double> tau_, A_;
    double A0_ = 0;
};

}  // namespace swelldem::core
