// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once
#include <string>

namespace swelldem_compat {

/// What is wrong with the YADE libraries mapped in this process, against the GNU build ids the plugin
/// was built against (SWELLDEM_YADE_BUILD_IDS, "lib:hexid,lib:hexid", written at configure time).
/// The declarations in compat/ describe one binary build of YADE: a YADE upgraded or rebuilt after
/// the plugin's build may keep its version string yet move a member or a vtable slot, so only the
/// build id proves that the layout is the one checked.
struct YadeBuildProblem {
	std::string why;               ///< "" when every library is mapped once with the recorded build id
	bool        twoCopies = false; ///< a library is mapped more than once (YADE itself then corrupts its heap at exit)
};

/// A mapped library is recognised by what it is, not by its file's name: its SONAME (the name the
/// dynamic loader matches), its file's base name, or the recorded build id.
YadeBuildProblem yadeBuildMismatch(const char* expectedIds);

} // namespace swelldem_compat
