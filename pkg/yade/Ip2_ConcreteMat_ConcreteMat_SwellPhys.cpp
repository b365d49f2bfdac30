// SPDX-License-Identifier: GPL-2.0-or-later
#include "Ip2_ConcreteMat_ConcreteMat_SwellPhys.hpp"
#include "SceneFunctors.hpp"
#include "core/PairKind.hpp"
#include "core/Validate.hpp"
#include <cstring>
#include <cmath>
#include <iostream>
#include <map>

namespace yade {

void Ip2_ConcreteMat_ConcreteMat_SwellPhys::postLoad() { swelldem::core::requirePositive("Ip2_ConcreteMat_ConcreteMat_SwellPhys.thickness [m]", thickness); }

namespace {
	using Ip2 = Ip2_ConcreteMat_ConcreteMat_SwellPhys;
	// The kind slots in core::PairKind's order: the attribute each kind of pair takes its ContactKind from.
	const std::pair<const char*, shared_ptr<ContactKind> Ip2::*> kSlots[swelldem::core::kPairKinds] = {
		{ "mortar", &Ip2::mortar }, { "itz", &Ip2::itz }, { "agg", &Ip2::agg }, { "platen", &Ip2::platen }, { "steel", &Ip2::steel }, { "bond", &Ip2::bond }
	};
	swelldem::core::PairMaterial pairMaterial(const ConcreteMat& m) { return { m.aggregateId, m.platen, m.steel }; }
}

const char* Ip2_ConcreteMat_ConcreteMat_SwellPhys::slotName(const ConcreteMat& a, const ConcreteMat& b)
{
	return kSlots[int(swelldem::core::pairKind(pairMaterial(a), pairMaterial(b)))].first;
}

const shared_ptr<ContactKind>& Ip2_ConcreteMat_ConcreteMat_SwellPhys::slot(const char* name) const
{
	for (const auto& s : kSlots)
		if (std::strcmp(s.first, name) == 0) return this->*s.second;
	static const shared_ptr<ContactKind> none;
	return none;
}

void Ip2_ConcreteMat_ConcreteMat_SwellPhys::go(const shared_ptr<Material>& m1, const shared_ptr<Material>& m2, const shared_ptr<Interaction>& I)
{
	// YADE calls this at every iteration of every contact: a contact made is left alone, unless it
	// was made without a kind (its slot was None), which is made again in case the slot is now set.
	if (I->phys) {
		const auto* made = dynamic_cast<const SwellPhys*>(I->phys.get());
		if (!made || made->kind) return;
	}
	const char*                    which = slotName(static_cast<const ConcreteMat&>(*m1), static_cast<const ConcreteMat&>(*m2));
	const shared_ptr<ContactKind>& kind  = slot(which);
	const auto*                    geom  = dynamic_cast<const ScGeom*>(I->geom.get());
	shared_ptr<SwellPhys>          p(new SwellPhys);
	if (geom) {
		p->length = geom->refR1 + geom->refR2 - geom->penetrationDepth;
		p->area   = 2 * std::min(geom->refR1, geom->refR2) * thickness;
		constexpr unsigned planar = State::DOF_Z | State::DOF_RX | State::DOF_RY;
		auto inPlane = [&](Body::id_t id) {
			const auto& b = scene->bodies->body[id];
			return b && (b->state->blockedDOFs & planar) == planar;
		};
		if (!inPlane(I->id1) || !inPlane(I->id2)) {
			p->dim = 3;
			Eigen::Index k = 2;
			geom->normal.cwiseAbs().minCoeff(&k);
			p->frameAxis = int(k);
			// a 3D contact without a Laguerre facet (made by the collider during a run, or a
			// platen's): the smaller sphere's cross-section, not a 2D section's 2 r b
			const Real r = std::min(geom->refR1, geom->refR2);
			p->area      = M_PI * r * r;
		}
	}
	// An Ip2 may not throw (YADE calls it inside its parallel loops), nor leave a contact without
	// physics (Debian's YADE aborts on its assertion I->phys): a contact it cannot make gets physics
	// without a kind, which carries no force, and the error is recorded for the log-time solvers to
	// raise after the loop (requireContactKinds refuses such a scene before their first step).
	if (!kind || !geom) {
		const string why = !kind ? "Ip2_ConcreteMat_ConcreteMat_SwellPhys." + string(which) + " = None is out of range (contact of bodies "
		                                   + std::to_string(I->id1) + " and " + std::to_string(I->id2) + "); allowed: a ContactKind"
		                         : string("Ip2_ConcreteMat_ConcreteMat_SwellPhys: the contact geometry must be ScGeom (Ig2_Sphere_Sphere_ScGeom)");
		recordFunctorError(why);
		// Under another integrator nothing raises it: say it once, on stderr.
		if (!warned_.exchange(true)) std::cerr << "swelldem: " << why << "; the contact carries no force" << std::endl;
		I->phys = p;
		return;
	}
	p->kind                   = kind;
	p->kindId                 = kind->kindId;
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

void requireContactKinds(Scene* scene, const string& solverName)
{
	// What the first pass of the engines recorded is covered by the checks below, and what an earlier
	// run or scene left is not this run's: the solver starts with no pending functor error.
	takeFunctorError();
	const string head = "swelldem: " + solverName + " cannot start: ";
	const auto ip2s = sceneFunctors<Ip2_ConcreteMat_ConcreteMat_SwellPhys>(scene, "physDispatcher");
	// The ConcreteMat materials of the bodies, with the first two bodies of each (a pair of one
	// material needs two of its bodies).
	std::map<const ConcreteMat*, std::vector<long>> bodiesOf;
	for (const auto& b : scene->bodies->body)
		if (b)
			if (const auto* m = dynamic_cast<const ConcreteMat*>(b->material.get())) {
				auto& ids = bodiesOf[m];
				if (ids.size() < 2) ids.push_back(b->id);
			}
	for (const auto& ip2 : ip2s)
		for (auto a = bodiesOf.begin(); a != bodiesOf.end(); ++a)
			for (auto b = a; b != bodiesOf.end(); ++b) {
				if (a == b && a->second.size() < 2) continue;
				const char* which = Ip2_ConcreteMat_ConcreteMat_SwellPhys::slotName(*a->first, *b->first);
				if (ip2->slot(which)) continue;
				const long u = a->second[0], v = a == b ? a->second[1] : b->second[0], i = std::min(u, v), j = std::max(u, v);
				throw std::invalid_argument(head + "Ip2_ConcreteMat_ConcreteMat_SwellPhys." + which + " = None is out of range; allowed: a ContactKind ("
				                            + "the scene's bodies " + std::to_string(i) + " and " + std::to_string(j) + " would make a contact of this kind; "
				                            + "set it before the run)");
			}
	const auto& L = scene->interactions->linIntrs;
	for (size_t k = 0; k < scene->interactions->currSize; ++k)
		if (L[k]->isReal())
			if (const auto* p = dynamic_cast<const SwellPhys*>(L[k]->phys.get()); p && !p->kind)
				throw std::invalid_argument(head + "the contact of bodies " + std::to_string(L[k]->id1) + " and " + std::to_string(L[k]->id2)
				                            + " has SwellPhys.kind = None; allowed: a ContactKind (its Ip2 slot was None or its geometry not "
				                              "ScGeom when it was made)");
}

} // namespace yade
