// SPDX-License-Identifier: GPL-2.0-or-later
// Creates SwellPhys for contacts between ConcreteMat particles and assigns the contact kind from the
// slot that core::pairKind (core/PairKind.hpp) names for the two materials: mortar-mortar MORTAR;
// mortar-aggregate or two different aggregates ITZ; one aggregate AGG; with a platen (a Wall of a
// ConcreteMat with platen set) PLATEN; two steel discs STEEL; steel and concrete BOND.
#pragma once
#include "ConcreteMat.hpp"
#include "SwellPhys.hpp"

namespace yade {

class Ip2_ConcreteMat_ConcreteMat_SwellPhys : public IPhysFunctor {
public:
#define SWELLDEM_IP2_ATTRS(X)                                                                                                                                  \
	X(shared_ptr<ContactKind>, mortar, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of mortar-mortar contacts (MORTAR) [-]")                                        \
	X(shared_ptr<ContactKind>, itz, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of mortar-aggregate and aggregate-aggregate contacts (ITZ) [-]")                   \
	X(shared_ptr<ContactKind>, agg, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of contacts inside one aggregate (AGG) [-]")                                       \
	X(shared_ptr<ContactKind>, platen, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of contacts with a platen (ConcreteMat.platen; PLATEN) [-]")                  \
	X(shared_ptr<ContactKind>, steel, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of contacts between two steel discs of a bar (ConcreteMat.steel; STEEL) [-]")    \
	X(shared_ptr<ContactKind>, bond, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of contacts between steel and concrete (BOND) [-]")                             \
	X(Real, thickness, 1.0, swelldem_attr::Setting, "Out-of-plane thickness b of the 2D model; fallback facet area 2 min(r1, r2) b when no Laguerre facet is given (3D: pi min(r1, r2)^2) [m]")      \
	X(bool, cohesive, true, swelldem_attr::Setting, "Contacts created while true are intact (bonded) and stress-free as created; while false they are born broken "   \
	                             "(compression and friction only) and stress-free when the discs just touch [-]")
	SWELLDEM_CLASS(Ip2_ConcreteMat_ConcreteMat_SwellPhys, IPhysFunctor,
	               "Creates SwellPhys between two ConcreteMat particles. The facet area is set to the fallback 2 min(r1, r2) "
	               "thickness; the mesostructure tools overwrite it with the Laguerre facet area before the first step. A kind "
	               "left None may be for pairs the scene does not have: the log-time solvers refuse, before their first step, an "
	               "Ip2 without a kind for a pair of the scene's materials; a contact made for a pair whose kind is None carries "
	               "no force (and is made again once the kind is set).",
	               SWELLDEM_IP2_ATTRS)
	virtual ~Ip2_ConcreteMat_ConcreteMat_SwellPhys() { }
	std::string get2DFunctorType1(void) const override { return "ConcreteMat"; }
	std::string get2DFunctorType2(void) const override { return "ConcreteMat"; }
	void        go(const shared_ptr<Material>& m1, const shared_ptr<Material>& m2, const shared_ptr<Interaction>& I) override;
	void        postLoad();
	template <class C> static void pyMethods(C&) { }
	/// The kind slot (the attribute's name) of the contacts between particles of materials a and b (core::pairKind).
	static const char* slotName(const ConcreteMat& a, const ConcreteMat& b);
	/// The slot's kind, or null.
	const shared_ptr<ContactKind>& slot(const char* name) const;

private:
	std::atomic<bool> warned_ { false }; // a contact left without a kind was reported on stderr
};

} // namespace yade
