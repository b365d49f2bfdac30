// SPDX-License-Identifier: GPL-2.0-or-later
#include "Ip2_ConcreteMat_ConcreteMat_SwellPhys.hpp"
#include "core/Validate.hpp"
#include <cmath>

namespace yade {

void Ip2_ConcreteMat_ConcreteMat_SwellPhys::postLoad() { swelldem::core::requirePositive("Ip2_ConcreteMat_ConcreteMat_SwellPhys.thickness [m]", thickness); }

void Ip2_ConcreteMat_ConcreteMat_SwellPhys::go(const shared_ptr<Material>& m1, const shared_ptr<Material>& m2, const shared_ptr<Interaction>& I)
{
	if (I->phys) return;
	const auto* a = static_cast<const ConcreteMat*>(m1.get());
	const auto* b = static_cast<const ConcreteMat*>(m2.get());
	// Platens first (a bar's end may touch one), then steel, then the concrete's own kinds.
	const bool  withPlaten = a->platen || b->platen, bothSteel = !withPlaten && a->steel && b->steel;
	const bool  withSteel = !withPlaten && !bothSteel && (a->steel || b->steel), concrete = !withPlaten && !bothSteel && !withSteel;
	const bool  mortar = concrete && a->isMortar() && b->isMortar(), sameAggregate = concrete && !mortar && a->aggregateId == b->aggregateId;
	const shared_ptr<ContactKind>& kind
	        = withPlaten ? platen : (bothSteel ? steel : (withSteel ? bond : (mortar ? this->mortar : (sameAggregate ? agg : itz))));
	const char* which = withPlaten ? "platen" : (bothSteel ? "steel" : (withSteel ? "bond" : (mortar ? "mortar" : (sameAggregate ? "agg" : "itz"))));
	const auto*                    geom = dynamic_cast<const ScGeom*>(I->geom.get());
	// An Ip2 may not throw (YADE calls it inside its parallel loops): a contact it cannot make is
	// left without physics and the log-time solvers raise the error after the loop.
	if (!kind || !geom) {
		recordFunctorError(!kind ? string("Ip2_ConcreteMat_ConcreteMat_SwellPhys.") + which
		                                   + " is not set (contact of bodies " + std::to_string(I->id1) + " and " + std::to_string(I->id2)
		                                   + "); allowed: a ContactKind"
		                         : string("Ip2_ConcreteMat_ConcreteMat_SwellPhys: the contact geometry must be ScGeom (Ig2_Sphere_Sphere_ScGeom)"));
		return;
	}
	shared_ptr<SwellPhys> p(new SwellPhys);
	p->kind                   = kind;
	p->kindId                 = kind->kindId;
	p->length                 = geom->refR1 + geom->refR2 - geom->penetrationDepth;
	p->area                   = 2 * std::min(geom->refR1, geom->refR2) * thickness;
	p->tangensOfFrictionAngle = std::tan(kind->table.strength.residualFrictionAngle);
	swelldem::core::ContactState& s = p->state;
	// Stiffness and step data come with the contact's first physical step (Law2).
	s.openingRef = s.opening = -geom->penetrationDepth;
	if (!cohesive) {
		// A contact made during the run is cohesionless and stress-free when the discs just touch.
		s.committed.broken = s.trial.broken = true;
		s.openingRef = s.opening = 0;
	}
	I->phys = p;
}

} // namespace yade
