// SPDX-License-Identifier: GPL-2.0-or-later
// One format for every parameter check of the physics core:
//   "swelldem: <param> = <value> is out of range; allowed: <range>"
// All checks throw std::invalid_argument. NaN never passes a check (every test is
// written as "value is inside", which is false for NaN).
#pragma once

#include <string>

namespace swelldem::core {

/// Throws std::invalid_argument("swelldem: <param> = <value> is out of range; allowed: <range>")
/// unless ok is true.
void require(bool ok, const std::string& param, double value, const std::string& range);

/// value > 0 (and finite).
void requirePositive(const std::string& param, double value);
/// value >= 0 (and finite).
void requireNonNegative(const std::string& param, double value);
/// lo < value < hi.
void requireOpenInterval(const std::string& param, double value, double lo, double hi);
/// value > lowerValue, the range text names the bound: "<param> > <lowerName> = <lowerValue>".
void requireGreater(const std::string& param, double value, const std::string& lowerName, double lowerValue);
/// value >= lowerValue, same message style.
void requireGreaterEqual(const std::string& param, double value, const std::string& lowerName,
                         double lowerValue);

/// Shortest round-trip text of a double (used in the messages).
std::string formatNumber(double value);

}  // namespace swelldem::core
