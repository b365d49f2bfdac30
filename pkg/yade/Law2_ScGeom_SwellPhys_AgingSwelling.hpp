// SPDX-License-Identifier: GPL-2.0-or-later
// The contact law of swelldem (the paper's eq. 10) in YADE's InteractionLoop: per physical step a
// constant incremental stiffness and a constant inelastic + swelling offset (set lazily at the
// contact's first iteration of the step), tension cut-off and the broken Coulomb state. The shear
// force is carried as YADE's incremental vector (rotated with the contact plane, as
// Law2_ScGeom_FrictPhys_CundallStrack does) and mirrored as the signed scalar SwellPhys.Fs.
#pragma once
#include "SwellPhys.hpp"

namespace yade {

class Law2_ScGeom_SwellPhys_AgingSwelling : public LawFunctor {
public:
#define SWELLDEM_LAW2_ATTRS(X) X(long, nBreaks, 0, "Contacts broken by this functor since the start; under AdrLogTimeIntegrator contacts break at equilibrium, counted by the integrator in ContactKind.breakEvents instead [-]")
	SWELLDEM_CLASS(Law2_ScGeom_SwellPhys_AgingSwelling, LawFunctor,
	               "Aging viscoelastic, swelling, brittle contact law of swelldem (normal and shear), over ScGeom and SwellPhys.",
	               SWELLDEM_LAW2_ATTRS)
	virtual ~Law2_ScGeom_SwellPhys_AgingSwelling() { }
	std::string get2DFunctorType1(void) const override { return "ScGeom"; }
	std::string get2DFunctorType2(void) const override { return "SwellPhys"; }
	bool        go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I) override;
	void        postLoad() { }
	template <class C> static void pyMethods(C&) { }
	/// Sets a contact up for its kind's current physical step (stiffness, offsets, trial = committed).
	static void beginContactStep(SwellPhys& p, const Vector3r& normal);
	/// Commits a converged step: hidden strains, committed forces, reference opening.
	static void commit(SwellPhys& p);
	/// Breaks an intact contact of a damaging kind whose unclamped forces exceed its strength, and
	/// counts it in its kind; returns whether it broke. The law calls it at every iteration, or
	/// AdrLogTimeIntegrator at equilibrium only (ContactKind.breaksAtEquilibrium).
	static bool breakIfOverloaded(SwellPhys& p, Real FnHat, Real shearMagnitude);
};

} // namespace yade
