// SPDX-License-Identifier: GPL-2.0-or-later
// Physical times evenly spaced in log time.
#pragma once

#include <vector>

namespace swelldem::core {

/// Times t_k = tStart 10^(k / stepsPerDecade) from tStart up to tEnd (tEnd always included),
/// merged with extraTimes (each within [tStart, tEnd]); sorted, duplicates (relative distance
/// < 1e-9) removed. Requires 0 < tStart < tEnd [day], 0 < stepsPerDecade <= 1e4.
std::vector<double> logTimes(double tStart, double tEnd, double stepsPerDecade,
                             const std::vector<double>& extraTimes = {});

}  // namespace swelldem::core
