// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/Validate.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace swelldem::core {

std::string formatNumber(double value)
{
    // the shortest representation that reads back identically; integers below 1e15 without exponent
    char buf[64];
    for (int prec = 1; prec <= 17; ++prec) {
        std::snprintf(buf, sizeof buf, "%.*g", prec, value);
        if (std::strtod(buf, nullptr) == value || !std::isfinite(value)) break;
    }
    if (std::strstr(buf, "e+") && std::fabs(value) < 1e15) std::snprintf(buf, sizeof buf, "%.0f", value);
    return buf;
}

void require(bool ok, const std::string& param, double value, const std::string& range)
{
    if (ok) return;
    throw std::invalid_argument("swelldem: " + param + " = " + formatNumber(value) +
                                " is out of range; allowed: " + range);
}

void requirePositive(const std::string& param, double value)
{
    require(value > 0 && std::isfinite(value), param, value, "0 < " + param + " < inf");
}

void requireNonNegative(const std::string& param, double value)
{
    require(value >= 0 && std::isfinite(value), param, value, "0 <= " + param + " < inf");
}

void requireOpenInterval(const std::string& param, double value, double lo, double hi)
{
    require(value > lo && value < hi, param, value,
            formatNumber(lo) + " < " + param + " < " + formatNumber(hi));
}

void requireGreater(const std::string& param, double value, const std::string& lowerName, double lowerValue)
{
    require(value > lowerValue && std::isfinite(value), param, value,
            param + " > " + lowerName + " = " + formatNumber(lowerValue));
}

void requireGreaterEqual(const std::string& param, double value, const std::string& lowerName,
                         double lowerValue)
{
    require(value >= lowerValue && std::isfinite(value), param, value,
            param + " >= " + lowerName + " = " + formatNumber(lowerValue));
}

}  // namespace swelldem::core
