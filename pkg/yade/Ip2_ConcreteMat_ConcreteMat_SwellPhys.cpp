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
	const shared_ptr<ContactKind>& kind = (a->isMortar() && b->isMortar()) ? mortar : (a->aggregateId == b->aggregateId ? agg : itz);
	const char* which = (a->isMortar() && b->isMortar()) ? "mortar" : (a->aggregateId == b->aggregateId ? "agg" : "itz");
	if (!kind) throw std::invalid_argument(string("Ip2_ConcreteMat_ConcreteMat_SwellPhys.") + which + " is not set: give it a ContactKind");
	const auto* geom = dynamic_cast<const ScGeom*>(I->geom.get());
	if (!geom) throw std::runtime_error("Ip2_ConcreteMat_ConcreteMat_SwellPhys: the contact geometry must be ScGeom (Ig2_Sphere_Sphere_ScGeom)");

	swelldem::core::ContactLaw& law = kind->law();
	shared_ptr<SwellPhys>       p(new SwellPhys);
	p->kind                   = kind;
	p->kindId                 = kind->kindId;
	p->length                 = geom->refR1 + geom->refR2 - geom->penetrationDepth;
	p->area                   = 2 * std::min(geom->refR1, geom->refR2) * thickness;
	p->uRef                   = -geom->penetrationDepth;
	p->uTrial                 = p->uRef;
	p->kn                     = law.stepModulus() * p->area / p->length;
	p->ks                     = kind->shearRatio * p->kn;
	p->tangensOfFrictionAngle = std::tan(kind->residualFrictionAngle);
	p->gamma.assign(law.hiddenStateSize(), 0.0);
	if (!cohesive) {
		// A contact made during the run is cohesionless and stress-free when the discs just touch.
		p->broken = p->committedBroken = true;
		p->uRef = p->uTrial = 0;
	}
	I->phys = p;
}

} // namespace yade
