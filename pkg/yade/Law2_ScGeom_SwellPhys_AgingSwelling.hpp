// SPDX-License-Identifier: GPL-2.0-or-later
// The contact law of swelldem (the paper's eq. 10) in YADE's InteractionLoop, a thin adapter over
// the physics core's ContactLaw: per physical step a constant incremental stiffness and a constant
// inelastic + swelling offset (set at the contact's first iteration of the step), tension cut-off
// and the broken Coulomb state, all computed by the core on the contact's own ContactState. The
// adapter keeps only what is YADE's: the shear force as YADE's incremental vector, rotated with the
// contact plane as Law2_ScGeom_FrictPhys_CundallStrack does, and the forces on the bodies.
// The functor owns what its scene's run does with the kinds (KindLaws: the step begun and a law per
// kind) and the modes a log-time solver chooses: it is present in every scene whose contacts are
// SwellPhys, under any integrator, and each scene has its own.
#pragma once
#include "KindLaws.hpp"
#include "SwellPhys.hpp"

namespace yade {

/// Whether the scene holds a log-time solver that has not begun its first step (its contacts wait
/// for it instead of building their kind's law with default settings).
bool logTimeSolverPending(const Scene* scene);

class Law2_ScGeom_SwellPhys_AgingSwelling : public LawFunctor {
public:
#define SWELLDEM_LAW2_ATTRS(X)                                                                                                                                 \
	X(long, nBreaks, 0, swelldem_attr::Result,                                                                                                           \
	  "Contacts broken since the start: by the law at once under other integrators, at equilibrium under the log-time solvers [-]")   \
	X(bool, breaksAtEquilibrium, false, swelldem_attr::Result,                                                                                           \
	  "Set by the log-time solvers: intact contacts break only at equilibrium; false under other integrators: the law breaks at once [-]")            \
	X(bool, shearFromStepStart, false, swelldem_attr::Result,                                                                                           \
	  "Set by ImplicitLogTimeSolver: the shear force is taken from the step's start (a broken contact's slip is decided by the state reached, "  \
	  "not by the iterations' path); false: YADE's incremental shear vector, whose slip is permanent at every iteration [-]")                      \
	X(StepWindow, window, StepWindow(), swelldem_attr::Internal, "The physical step the run has begun (its laws are rebuilt from it after O.load; read through stepSerial etc.) [-]")
	SWELLDEM_CLASS(Law2_ScGeom_SwellPhys_AgingSwelling, LawFunctor,
	               "Aging viscoelastic, swelling, brittle contact law of swelldem (normal and shear), over ScGeom and SwellPhys.",
	               SWELLDEM_LAW2_ATTRS)
	virtual ~Law2_ScGeom_SwellPhys_AgingSwelling() { }
	std::string get2DFunctorType1(void) const override { return "ScGeom"; }
	std::string get2DFunctorType2(void) const override { return "SwellPhys"; }
	bool        go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I) override;
	void        postLoad() { }
	template <class C> static void pyMethods(C& cls)
	{
		cls.add_property("stepSerial", +[](const Law2_ScGeom_SwellPhys_AgingSwelling& l) { return l.window.serial; },
		                 "(result) Physical steps begun by the run; a contact's step data belong to SwellPhys.stepSerial [-]");
		cls.add_property("stepStart", +[](const Law2_ScGeom_SwellPhys_AgingSwelling& l) { return l.window.start; },
		                 "(result) Start of the physical step begun (0: none; the laws then act at age 28 days) [day]");
		cls.add_property("stepEnd", +[](const Law2_ScGeom_SwellPhys_AgingSwelling& l) { return l.window.end; },
		                 "(result) End of the physical step begun [day]");
		cls.add_property("shortestLag", +[](const Law2_ScGeom_SwellPhys_AgingSwelling& l) { return l.window.shortestLag; },
		                 "(result) Shortest load duration the Kelvin chains resolve (the log-time solver's first step) [day]");
		cls.add_property("longestLag", +[](const Law2_ScGeom_SwellPhys_AgingSwelling& l) { return l.window.longestLag; },
		                 "(result) Longest load duration the Kelvin chains resolve (the run's span) [day]");
		cls.def("chainSize", &Law2_ScGeom_SwellPhys_AgingSwelling::chainSize, boost::python::arg("kind"),
		        "Kelvin units per direction of kind's law in this run (0 unless viscoelastic) [-].");
	}
	/// The run's laws, for the step `window`.
	KindLaws                    laws { window };
	swelldem::core::ContactLaw& lawFor(const ContactKind& kind) { return laws.lawFor(kind); }
	/// A log-time solver's modes: breaks at equilibrium only, and the shear from the step's start
	/// (ImplicitLogTimeSolver, but for a step it hands to dynamic relaxation) or incremental.
	void setLogTimeModes(bool fromStepStart);
	/// Commits a converged step (hidden strains, committed forces, reference opening).
	void commit(SwellPhys& p);
	/// At equilibrium (the log-time solvers): breaks an intact contact of a damaging kind whose
	/// forces exceed its strength and counts it; returns whether it broke.
	bool breakIfOverloaded(SwellPhys& p);
	int  chainSize(const shared_ptr<ContactKind>& kind);
	/// A 3D contact's tangents (SwellPhys.frameAxis): ek x n, normalised, then n x t1; for k = z the
	/// first is the 2D tangent ez x n. Its shear components Fs, Fs2 are along them.
	static std::pair<Vector3r, Vector3r> tangents(const Vector3r& n, int axis)
	{
		const Vector3r t1 = Vector3r::Unit(axis).cross(n).normalized();
		return { t1, n.cross(t1) };
	}

private:
	void beginContactStep(SwellPhys& p, const Vector3r& normal);
};

/// The scene's one Law2_ScGeom_SwellPhys_AgingSwelling (found in its InteractionLoops); throws
/// std::invalid_argument naming `solverName` when there is none or more than one.
Law2_ScGeom_SwellPhys_AgingSwelling* sceneLaw(Scene* scene, const string& solverName);

} // namespace yade
