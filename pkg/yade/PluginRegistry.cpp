// SPDX-License-Identifier: GPL-2.0-or-later
// The one list of swelldem's YADE classes: each is registered with YADE's ClassFactory, exported
// to boost::serialization, and announced to YADE, which then exposes it in Python at start-up.
#include "AdrLogTimeIntegrator.hpp"
#include "ImplicitLogTimeSolver.hpp"
#include "ConcreteMat.hpp"
#include "ContactKind.hpp"
#include "Ip2_ConcreteMat_ConcreteMat_SwellPhys.hpp"
#include "Law2_ScGeom_SwellPhys_AgingSwelling.hpp"
#include "SwellPhys.hpp"
#include "SwelldemAbiProbe.hpp"
#include "compat/YadeBuildCheck.hpp"

#include <cstdlib>
#include <iostream>

#define SWELLDEM_PLUGIN_CLASSES(X)                                                                                                                             \
	X(ConcreteMat)                                                                                                                                         \
	X(ContactKind)                                                                                                                                         \
	X(SwellPhys)                                                                                                                                           \
	X(Ip2_ConcreteMat_ConcreteMat_SwellPhys)                                                                                                               \
	X(Law2_ScGeom_SwellPhys_AgingSwelling)                                                                                                                 \
	X(LogTimeSolver)                                                                                                                                       \
	X(AdrLogTimeIntegrator)                                                                                                                                \
	X(ImplicitLogTimeSolver)                                                                                                                               \
	X(SwelldemAbiProbe)

namespace yade {
#define SWELLDEM_REGISTER(C) static swelldem_py::FactoryRegistration<C> registration_##C(#C);
SWELLDEM_PLUGIN_CLASSES(SWELLDEM_REGISTER)
#undef SWELLDEM_REGISTER

__attribute__((constructor)) static void announceSwelldemClasses()
{
	// Announcing the classes to a YADE whose binary layout is not the one the declarations were
	// checked against would let Python build objects that YADE reads at the wrong offsets; the plugin
	// stays silent instead, and says why once. YADE loads its own libraries (its folder's top level)
	// before this plugin (in a subfolder), so every copy that will be mapped is mapped by now.
	const auto problem = swelldem_compat::yadeBuildMismatch(SWELLDEM_YADE_BUILD_IDS);
	if (problem.twoCopies) {
		// Two copies of a YADE library each register YADE's classes and singletons, and the process
		// dies at exit ("double free or corruption") after whatever it computed: stop before any work.
		std::cerr << "swelldem: refusing to run: YADE's libraries are loaded twice in this process (" << problem.why
		          << "each copy frees YADE's shared state at exit). Run without LD_LIBRARY_PATH pointing to a copy of YADE's libraries."
		          << std::endl;
		std::_Exit(2);
	}
	if (!problem.why.empty()) {
		std::cerr << "swelldem: refusing to load: the running YADE is not the build this plugin was compiled for (" << problem.why
		          << "YADE was upgraded or replaced after the build). The plugin's classes are not available; rebuild: bash scripts/setup.sh"
		          << std::endl;
		return;
	}
#define SWELLDEM_NAME(C) #C,
	static const char* fileAndClasses[] = { __FILE__, SWELLDEM_PLUGIN_CLASSES(SWELLDEM_NAME) nullptr };
#undef SWELLDEM_NAME
	ClassFactory::instance().registerPluginClasses(fileAndClasses);
}
} // namespace yade

// The plugin's version as each class's Boost class version (compat/Plugin.hpp, requireSceneVersion).
// Written out instead of BOOST_CLASS_VERSION, whose 8-bit limit dates from archive formats older than
// YADE's (Boost 1.74 stores a class version in 32 bits). Only this file instantiates the serializers.
#define SWELLDEM_SCENE_VERSION_OF(C)                                                                                                                           \
	template <> struct boost::serialization::version<yade::C> {                                                                                          \
		typedef mpl::int_<SWELLDEM_SCENE_VERSION> type;                                                                                                \
		typedef mpl::integral_c_tag                tag;                                                                                                \
		BOOST_STATIC_CONSTANT(int, value = type::value);                                                                                               \
	};
SWELLDEM_PLUGIN_CLASSES(SWELLDEM_SCENE_VERSION_OF)
#undef SWELLDEM_SCENE_VERSION_OF

SWELLDEM_PLUGIN_CLASSES(SWELLDEM_EXPORT_SERIALIZATION)
