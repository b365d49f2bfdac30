// SPDX-License-Identifier: GPL-2.0-or-later
// Material of a concrete component particle: mortar, or one coarse aggregate (each aggregate has its
// own ConcreteMat instance so that Ip2 can tell two particles of the same aggregate (AGG contact)
// from two different aggregates (ITZ contact)).
#pragma once
#include "compat/Plugin.hpp"

namespace yade {

class ConcreteMat : public FrictMat {
public:
#define SWELLDEM_CONCRETE_MAT_ATTRS(X)                                                                                                                         \
	X(int, aggregateId, -1, swelldem_attr::Setting, "Aggregate this material belongs to: -1 for mortar, >= 0 for the particles of one coarse aggregate [-]") \
	X(bool, platen, false, swelldem_attr::Setting,                                                                                                        \
	  "A loading platen (a Wall body): its contacts are of the Ip2's platen kind (PLATEN), whatever the other material; aggregateId is then unused [-]") \
	X(bool, steel, false, swelldem_attr::Setting,                                                                                                         \
	  "Reinforcing steel (the discs of a bar): steel-steel contacts are of the Ip2's steel kind (STEEL), steel-concrete ones of its bond kind (BOND) [-]")
	SWELLDEM_CLASS(ConcreteMat, FrictMat,
	               "Concrete component (mortar or one coarse aggregate) of a swelldem mesostructure, a reinforcing bar's steel or a loading platen. Contact parameters are "
	               "not here but in the ContactKind objects of Ip2_ConcreteMat_ConcreteMat_SwellPhys (MORTAR, ITZ, AGG).",
	               SWELLDEM_CONCRETE_MAT_ATTRS)
	ConcreteMat() { createIndex(); }
	virtual ~ConcreteMat() { }
	bool isMortar() const { return aggregateId < 0; }
	void postLoad();
	template <class C> static void pyMethods(C&) { }
	SWELLDEM_CLASS_INDEX(ConcreteMat, FrictMat)
};

} // namespace yade
