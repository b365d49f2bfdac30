// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/LogTimes.hpp"

#include "core/Validate.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace swelldem::core {

std::vector<double> logTimes(double tStart, double tEnd, double stepsPerDecade,
                             const std::vector<double>& extraTimes)
{
    requirePositive("tStart [day]", tStart);
    requireGreater("tEnd [day]", tEnd, "tStart", tStart);
    require(stepsPerDecade > 0 && stepsPerDecade <= 1e4, "stepsPerDecade", stepsPerDecade,
            "0 < stepsPerDecade <= 10000");
    for (std::size_t i = 0; i < extraTimes.size(); ++i) {
        const double e = extraTimes[i];
        require(e >= tStart && e <= tEnd, "extraTimes[" + std::to_string(i) + "] [day]", e,
                formatNumber(tStart) + " <= t <= " + formatNumber(tEnd) + " (tStart..tEnd)");
    }
    std::vector<double> t;
    const double decades = std::log10(tEnd / tStart);
    const long nSteps = static_cast<long>(std::ceil(decades * stepsPerDecade - 1e-9));
    t.reserve(static_cast<std::size_t>(nSteps) + 1 + extraTimes.size());
    for (long k = 0; k < nSteps; ++k) t.push_back(tStart * std::pow(10.0, k / stepsPerDecade));
    t.push_back(tEnd);
    t.insert(t.end(), extraTimes.begin(), extraTimes.end());
    std::sort(t.begin(), t.end());
    std::vector<double> out;
    out.reserve(t.size());
    for (double v : t)
        if (out.empty() || v - out.back() > 1e-9 * v) out.push_back(v);
    if (out.back() != tEnd) out.back() = tEnd;  // a near-duplicate of tEnd keeps tEnd exactly
    return out;
}

}  // namespace swelldem::core
