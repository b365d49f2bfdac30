// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once
#include <string>

namespace swelldem_compat {

/// Compares the GNU build ids of the YADE libraries loaded in this process with those the plugin
/// was built against (SWELLDEM_YADE_BUILD_IDS, "lib:hexid,lib:hexid", written at configure time).
/// The declarations in compat/ describe one binary build of YADE: a YADE upgraded or rebuilt after
/// the plugin's build may keep its version string yet move a member or a vtable slot, so only the
/// build id proves that the layout is the one checked. Returns "" when all match, else the reason.
std::string yadeBuildMismatch(const char* expectedIds);

} // namespace swelldem_compat
