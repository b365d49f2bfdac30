// SPDX-License-Identifier: GPL-2.0-or-later
#include "ConcreteMat.hpp"
#include "core/Validate.hpp"

namespace yade {
void ConcreteMat::postLoad() { swelldem::core::require(aggregateId >= -1, "ConcreteMat.aggregateId", aggregateId, "-1 (mortar) or >= 0"); }
} // namespace yade
