// SPDX-License-Identifier: GPL-2.0-or-later
#include "SwellPhys.hpp"
#include "core/Validate.hpp"

namespace yade {

void SwellPhys::postLoad()
{
	// A contact made by the Ip2 gets its geometry right after; zero means "not set yet".
	if (area != 0) swelldem::core::requirePositive("SwellPhys.area [m2]", area);
	if (length != 0) swelldem::core::requirePositive("SwellPhys.length [m]", length);
	if (!(swellDispInf < 0)) swelldem::core::requireNonNegative("SwellPhys.swellDispInf [m]", swellDispInf);
}

} // namespace yade
