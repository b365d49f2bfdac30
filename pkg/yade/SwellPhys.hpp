// SPDX-License-Identifier: GPL-2.0-or-later
// Physics of one concrete contact: FrictPhys (so YADE's tools that read kn, ks, normalForce and
// shearForce keep working) plus the contact's kind, facet and its state. The state (forces,
// committed and trial, creep variables, the step's stiffness and offsets) is the physics core's
// ContactState, held here once: the law updates it in place, Python reads it through the
// properties below, and it is saved with the scene.
#pragma once
#include "ContactKind.hpp"

namespace boost::serialization {
// The core stays free of boost: its state is serialized from here.
template <class Archive> void serialize(Archive& ar, swelldem::core::ContactForces& f, unsigned)
{
	int mode = int(f.mode);
	ar& make_nvp("Fn", f.Fn);
	ar& make_nvp("Fs", f.Fs);
	ar& make_nvp("Fs2", f.Fs2);
	ar& make_nvp("FnHat", f.FnHat);
	ar& make_nvp("broken", f.broken);
	ar& make_nvp("mode", mode);
	f.mode = swelldem::core::FailureMode(mode);
}
template <class Archive> void serialize(Archive& ar, swelldem::core::ContactState& s, unsigned)
{
	ar& make_nvp("committed", s.committed);
	ar& make_nvp("trial", s.trial);
	ar& make_nvp("gamma", s.gamma);
	ar& make_nvp("kn", s.kn);
	ar& make_nvp("ks", s.ks);
	ar& make_nvp("duOffsetN", s.duOffsetN);
	ar& make_nvp("duOffsetS", s.duOffsetS);
	ar& make_nvp("duOffsetS2", s.duOffsetS2);
	ar& make_nvp("openingRef", s.openingRef);
	ar& make_nvp("opening", s.opening);
	ar& make_nvp("shearStep", s.shearStep);
	ar& make_nvp("shearStep2", s.shearStep2);
	ar& make_nvp("imposedOpeningRef", s.imposedOpeningRef);
}
} // namespace boost::serialization
BOOST_CLASS_IMPLEMENTATION(swelldem::core::ContactForces, boost::serialization::object_serializable)
BOOST_CLASS_TRACKING(swelldem::core::ContactForces, boost::serialization::track_never)
BOOST_CLASS_IMPLEMENTATION(swelldem::core::ContactState, boost::serialization::object_serializable)
BOOST_CLASS_TRACKING(swelldem::core::ContactState, boost::serialization::track_never)

namespace yade {

class SwellPhys : public FrictPhys {
public:
#define SWELLDEM_SWELL_PHYS_ATTRS(X)                                                                                                                           \
	X(shared_ptr<ContactKind>, kind, shared_ptr<ContactKind>(), swelldem_attr::Setting, "Kind of the contact (shared parameters) [-]")                   \
	X(int, kindId, 0, swelldem_attr::Result, "kind.kindId when the contact was made (see ContactKind.kindId) [-]")                        \
	X(Real, area, 0.0, swelldem_attr::Setting, "Contact facet area A_c (Laguerre facet length x thickness b) [m2]")                                     \
	X(Real, length, 0.0, swelldem_attr::Setting, "Centre distance L of the stress-free configuration; kn = E A / L [m]")                                 \
	X(Real, swellDispInf, -1.0, swelldem_attr::Setting,                                                                                                  \
	  "Per-contact ultimate swelling displacement d_inf; < 0: the kind's ContactKind.swellDispInf [m]")                                                  \
	X(Real, swellFactor, 1.0, swelldem_attr::Setting,                                                                                                    \
	  "Factor f on the swelling increment of the coming step, d_inf f dxi: the water the reaction finds (swelldem.dem.humidity sets it "  \
	  "from the local relative humidity before each step; 1: saturated); gel formed before stays [-]")                                        \
	X(Real, imposedOpening, 0.0, swelldem_attr::Setting,                                                                                                 \
	  "Imposed free normal opening at the end of the coming step, a total since the contact was made (drying shrinkage: < 0); the step "  \
	  "imposes its change since the last converged step (swelldem.dem.humidity sets it) [m]")                                                  \
	X(int, dim, 2, swelldem_attr::Result,                                                                                                                 \
	  "2: a contact of a 2D section (both bodies with z translation and x, y rotations blocked), one shear component along "             \
	  "ez x normal; 3: a 3D contact, shear along two tangents of its facet (set when the contact is made) [-]")                                \
	X(int, frameAxis, 2, swelldem_attr::Internal,                                                                                                        \
	  "A 3D contact's first tangent is ek x normal, normalised, for this axis k, the one most nearly in the facet when the contact was "     \
	  "made: the tangents then turn with the normal, away from their singularity, and the shear components keep their meaning [-]")         \
	X(long, stepSerial, -1, swelldem_attr::Result, "Physical step (Law2_ScGeom_SwellPhys_AgingSwelling.stepSerial) the contact's step data belong to [-]")                      \
	X(swelldem::core::ContactState, state, swelldem::core::ContactState(), swelldem_attr::Internal, "The contact's state (physics core) [-]")
	SWELLDEM_CLASS(SwellPhys, FrictPhys,
	               "Concrete contact of swelldem: aging viscoelastic (B3, solidification theory), swelling (Larive) and brittle. "
	               "Forces follow YADE's FrictPhys convention (normalForce, shearForce vectors) and are given as signed "
	               "scalars Fn (tension positive) and Fs.",
	               SWELLDEM_SWELL_PHYS_ATTRS)
	SwellPhys() { createIndex(); }
	virtual ~SwellPhys() { }
	void postLoad();
	/// What Python may set kind to (compat/Plugin.hpp): a ContactKind.
	void checkObject(const char* name, const shared_ptr<ContactKind>& value) const;
	template <class C> static void pyMethods(C& cls)
	{
		using S = swelldem::core::ContactState;
		cls.add_property("kindName", &SwellPhys::kindName, "Name of the contact's kind [-]");
		cls.add_property("swellingDispInf", &SwellPhys::effectiveSwellDispInf, "Ultimate swelling displacement in force (own or the kind's) [m]");
		cls.add_property("fnMax", &SwellPhys::fnMax, "Tensile strength of the contact f_t A (inf when damage is off) [N]");
		cls.add_property("Fn", +[](const SwellPhys& p) { return p.state.trial.Fn; }, "(result) Transmitted normal force, tension positive [N]");
		cls.add_property("Fs", +[](const SwellPhys& p) { return p.state.trial.Fs; },
		                 "(result) Transmitted shear force along the first tangent (2D: ez x normal; 3D: see frameAxis) [N]");
		cls.add_property("Fs2", +[](const SwellPhys& p) { return p.state.trial.Fs2; },
		                 "(result) Transmitted shear force along the second tangent, normal x first (3D; 0 in 2D) [N]");
		cls.add_property("FnHat", +[](const SwellPhys& p) { return p.state.trial.FnHat; },
		                 "(result) Unclamped normal force; > 0 on a broken contact measures how far its crack is open [N]");
		cls.add_property("broken", +[](const SwellPhys& p) { return p.state.trial.broken; }, "(result) Broken (committed or during this step) [-]");
		cls.add_property("failureMode", +[](const SwellPhys& p) { return int(p.state.trial.mode); }, "(result) How it broke: 0 intact, 1 tension, 2 shear [-]");
		cls.add_property("committedFn", +[](const SwellPhys& p) { return p.state.committed.Fn; }, "(result) Normal force at the end of the last converged step [N]");
		cls.add_property("committedFs", +[](const SwellPhys& p) { return p.state.committed.Fs; }, "(result) Shear force at the end of the last converged step [N]");
		cls.add_property("committedFs2", +[](const SwellPhys& p) { return p.state.committed.Fs2; },
		                 "(result) Shear force along the second tangent at the end of the last converged step (3D) [N]");
		cls.add_property("committedBroken", +[](const SwellPhys& p) { return p.state.committed.broken; }, "(result) Broken at the end of the last converged step [-]");
		cls.add_property("gamma", +[](const SwellPhys& p) { return std::vector<Real>(p.state.gamma.begin(), p.state.gamma.end()); },
		                 "(result) Hidden Kelvin-chain strains, normal units then those of each shear component (empty unless viscoelastic) [-]");
		cls.add_property("uRef", +[](const SwellPhys& p) { return p.state.openingRef; }, +[](SwellPhys& p, Real v) { p.state.openingRef = v; },
		                 "Normal opening (-penetrationDepth) at which the committed force was reached: the stress-free opening at "
		                 "creation (set it before the first step to choose another), then the converged opening of each step [m]");
		cls.add_property("imposedOpeningRef", +[](const SwellPhys& p) { return p.state.imposedOpeningRef; },
		                 "(result) imposedOpening at the end of the last converged step [m]");
		cls.add_property("duOffsetN", +[](const SwellPhys& p) { return p.state.duOffsetN; }, +[](SwellPhys& p, Real v) { p.state.duOffsetN = v; },
		                 "Step data: inelastic + swelling normal displacement increment of the current step (opening > 0); set by the step "
		                 "set-up, writable for experiments [m]");
		cls.add_property("duOffsetS", +[](const SwellPhys& p) { return p.state.duOffsetS; }, +[](SwellPhys& p, Real v) { p.state.duOffsetS = v; },
		                 "Step data: inelastic shear displacement increment of the current step; writable for experiments [m]");
		cls.add_property("duOffsetS2", +[](const SwellPhys& p) { return p.state.duOffsetS2; }, +[](SwellPhys& p, Real v) { p.state.duOffsetS2 = v; },
		                 "Step data: the same along the second tangent (3D); writable for experiments [m]");
		// kn, ks: the step stiffnesses live in the state; YADE's own kn, ks members mirror them for YADE's tools.
		cls.add_property("kn", +[](const SwellPhys& p) { return p.state.kn; }, +[](SwellPhys& p, Real v) { p.state.kn = p.NormPhys::kn = v; },
		                 "Step data: incremental normal stiffness kn'' of the current step; writable for experiments [N/m]");
		cls.add_property("ks", +[](const SwellPhys& p) { return p.state.ks; }, +[](SwellPhys& p, Real v) { p.state.ks = p.NormShearPhys::ks = v; },
		                 "Step data: incremental shear stiffness ks'' of the current step; writable for experiments [N/m]");
		(void)sizeof(S);
	}
	string kindName() const { return kind ? kind->name : string(); }
	Real   effectiveSwellDispInf() const { return swellDispInf >= 0 ? swellDispInf : (kind ? kind->table.swellingDisplacementInf : 0.0); }
	Real   fnMax() const { return kind && kind->table.strength.damage ? kind->table.strength.tensileStrength * area : std::numeric_limits<Real>::infinity(); }
	swelldem::core::ContactGeometry geometry() const
	{
		swelldem::core::ContactGeometry g;
		g.area                    = area;
		g.length                  = length;
		g.swellingDisplacementInf = swellDispInf;
		g.swellingFactor          = swellFactor;
		g.imposedOpening          = imposedOpening;
		g.shearComponents         = dim == 3 ? 2 : 1;
		return g;
	}
	SWELLDEM_CLASS_INDEX(SwellPhys, FrictPhys)
};

/// Before a log-time solver's first step: every Ip2_ConcreteMat_ConcreteMat_SwellPhys of the scene's
/// engines has a kind for each pair of ConcreteMat materials of its bodies, and every SwellPhys has
/// a kind; throws std::invalid_argument naming the missing slot and two bodies that need it. Errors
/// the functors recorded before the solver began (a contact made without a kind) are its own.
/// (Defined with the Ip2, whose slots it checks; declared here for the solvers, which include this.)
void requireContactKinds(Scene* scene, const string& solverName);

} // namespace yade
