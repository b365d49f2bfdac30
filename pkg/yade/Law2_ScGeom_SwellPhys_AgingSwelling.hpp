// SPDX-License-Identifier: GPL-2.0-or-later
// The contact law of swelldem (the paper's eq. 10) in YADE's InteractionLoop, a thin adapter over
// the physics core's ContactLaw: per physical step a constant incremental stiffness and a constant
// inelastic + swelling offset (set at the contact's first iteration of the step), tension cut-off
// and the broken Coulomb state, all computed by the core on the contact's own ContactState. The
// adapter keeps only what is YADE's: the shear force as YADE's incremental vector, rotated with the
// contact plane as Law2_ScGeom_FrictPhys_CundallStrack does, and the forces on the bodies.
#pragma once
#include "SwellPhys.hpp"

namespace yade {

/// Whether the scene holds a log-time solver that has not begun its first step (its contacts wait
/// for it instead of building their kind's law with default settings).
bool logTimeSolverPending(const Scene* scene);

class Law2_ScGeom_SwellPhys_AgingSwelling : public LawFunctor {
public:
#define SWELLDEM_LAW2_ATTRS(X)                                                                                                                                 \
	X(long, nBreaks, 0, swelldem_attr::Result,                                                                                                           \
	  "Contacts broken by this functor since the start; under the log-time solvers contacts break at equilibrium, counted in "                      \
	  "ContactKind.breakEvents instead [-]")
	SWELLDEM_CLASS(Law2_ScGeom_SwellPhys_AgingSwelling, LawFunctor,
	               "Aging viscoelastic, swelling, brittle contact law of swelldem (normal and shear), over ScGeom and SwellPhys.",
	               SWELLDEM_LAW2_ATTRS)
	virtual ~Law2_ScGeom_SwellPhys_AgingSwelling() { }
	std::string get2DFunctorType1(void) const override { return "ScGeom"; }
	std::string get2DFunctorType2(void) const override { return "SwellPhys"; }
	bool        go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I) override;
	void        postLoad() { }
	template <class C> static void pyMethods(C&) { }
	/// Commits a converged step (hidden strains, committed forces, reference opening).
	static void commit(SwellPhys& p);
	/// At equilibrium (the log-time solvers): breaks an intact contact of a damaging kind whose
	/// forces exceed its strength and counts it in its kind; returns whether it broke.
	static bool breakIfOverloaded(SwellPhys& p);

private:
	static void beginContactStep(SwellPhys& p, const Vector3r& normal);
};

} // namespace yade
