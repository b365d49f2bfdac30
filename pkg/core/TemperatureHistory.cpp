// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/TemperatureHistory.hpp"

#include "core/Validate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace swelldem::core {

TemperatureHistory::TemperatureHistory(std::vector<double> days, std::vector<double> temperatures)
    : days_(std::move(days)), temps_(std::move(temperatures))
{
    validate(days_, temps_);
    constant_ = std::all_of(temps_.begin(), temps_.end(), [&](double T) { return T == temps_.front(); });
}

void TemperatureHistory::validate(const std::vector<double>& days, const std::vector<double>& temperatures)
{
    require(temperatures.size() == days.size(), "len(temperatures)", static_cast<double>(temperatures.size()),
            "len(temperatureDays) = " + std::to_string(days.size()) + " (one temperature per day)");
    for (std::size_t i = 0; i < days.size(); ++i) {
        const std::string d = "temperatureDays[" + std::to_string(i) + "] [day]";
        if (i == 0) requireNonNegative(d, days[0]);
        else requireGreater(d, days[i], "temperatureDays[" + std::to_string(i - 1) + "]", days[i - 1]);
        const std::string T = "temperatures[" + std::to_string(i) + "]";
        require(temperatures[i] > 0 && temperatures[i] <= kMaxTemperature, T + " [K]", temperatures[i],
                "0 < " + T + " <= " + formatNumber(kMaxTemperature) + " [K] (above 0 K, at most 100 C)");
    }
}

std::ptrdiff_t TemperatureHistory::segment(double t) const
{
    return static_cast<std::ptrdiff_t>(std::upper_bound(days_.begin(), days_.end(), t) - days_.begin()) - 1;
}

double TemperatureHistory::at(double t) const
{
    const std::ptrdiff_t j = segment(t);
    if (j < 0) return temps_.front();
    const std::size_t k = static_cast<std::size_t>(j);
    if (k + 1 >= days_.size()) return temps_.back();
    const double a = (t - days_[k]) / (days_[k + 1] - days_[k]);
    return temps_[k] + a * (temps_[k + 1] - temps_[k]);
}

namespace {
// 8-point Gauss-Legendre on [-1, 1]
constexpr double kGlX[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kGlW[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
constexpr double kPanelKelvin = 5.0;  // largest temperature change over one Gauss-Legendre panel
}  // namespace

ArrheniusTime::ArrheniusTime(const TemperatureHistory& history, double U, double T0) : h_(history), U_(U), T0_(T0)
{
    requireNonNegative("U [K]", U);
    requirePositive("T0 [K]", T0);
    const auto& d = h_.days();
    cumulative_.resize(d.size());
    double s = 0, a = 0;
    for (std::size_t j = 0; j < d.size(); ++j) {
        s += piece(a, d[j]);
        cumulative_[j] = s;
        a = d[j];
    }
}

double ArrheniusTime::factor(double T) const { return std::exp(U_ * (1.0 / T0_ - 1.0 / T)); }

double ArrheniusTime::piece(double a, double b) const
{
    if (!(b > a)) return 0.0;
    const double Ta = h_.at(a), Tb = h_.at(b);
    if (Ta == Tb) return factor(Ta) * (b - a);
    const int panels = std::max(1, static_cast<int>(std::ceil(std::fabs(Tb - Ta) / kPanelKelvin)));
    const double h = (b - a) / panels, dT = (Tb - Ta) / panels;
    double s = 0;
    for (int p = 0; p < panels; ++p) {
        // T is linear in t over the piece: the panel's nodes in temperature directly
        const double Tc = Ta + (p + 0.5) * dT;
        for (int i = 0; i < 4; ++i)
            s += kGlW[i] * (factor(Tc - 0.5 * dT * kGlX[i]) + factor(Tc + 0.5 * dT * kGlX[i]));
    }
    return 0.5 * h * s;
}

double ArrheniusTime::integral(double t1, double t2) const
{
    requireNonNegative("t1 [day]", t1);
    requireGreaterEqual("t2 [day]", t2, "t1", t1);
    if (h_.empty()) return t2 - t1;
    if (h_.isConstant()) return factor(h_.temperatures().front()) * (t2 - t1);
    const auto& d = h_.days();
    double s = 0, a = t1;
    for (std::size_t k = static_cast<std::size_t>(h_.segment(t1) + 1); k < d.size() && d[k] < t2; ++k) {
        s += piece(a, d[k]);
        a = d[k];
    }
    return s + piece(a, t2);
}

double ArrheniusTime::at(double t) const
{
    requireNonNegative("t [day]", t);
    if (h_.empty()) return t;
    if (h_.isConstant()) return factor(h_.temperatures().front()) * t;
    const std::ptrdiff_t j = h_.segment(t);
    if (j < 0) return piece(0.0, t);
    const std::size_t k = static_cast<std::size_t>(j);
    return cumulative_[k] + piece(h_.days()[k], t);
}

}  // namespace swelldem::core
