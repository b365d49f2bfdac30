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
	swelldem::core::require(dim == 2 || dim == 3, "SwellPhys.dim", dim, "2 or 3");
	swelldem::core::require(frameAxis >= 0 && frameAxis <= 2, "SwellPhys.frameAxis", frameAxis, "0, 1 or 2");
}

void SwellPhys::checkObject(const char*, const shared_ptr<ContactKind>& value) const
{
	// Every user of a contact (the law, the solvers' set-up, commit and breaks, the implicit solver's
	// tangent) reads its kind: Python cannot take it away. (A default-made or loaded SwellPhys may have
	// none; the law guards it, and the log-time solvers refuse such a contact before their first step.)
	// Any other kind is taken, one new to the scene too: the run's law functor builds its law for the
	// step begun, and the contact takes up the kind's step data at the next step.
	if (!value)
		throw std::invalid_argument("swelldem: SwellPhys.kind = None is out of range; allowed: a ContactKind (a contact cannot be left "
		                            "without its kind; assign another ContactKind to change it)");
}

} // namespace yade
