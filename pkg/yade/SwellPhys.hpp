// SPDX-License-Identifier: GPL-2.0-or-later
// Physics of one concrete contact: FrictPhys (so YADE's tools that read kn, ks, normalForce and
// shearForce keep working) plus the contact's kind, facet, strength state and creep state, kept as
// a committed part (end of the last converged physical step) and a trial part (current iteration).
#pragma once
#include "ContactKind.hpp"

namespace yade {

class SwellPhys : public FrictPhys {
public:
#define SWELLDEM_SWELL_PHYS_ATTRS(X)                                                                                                                           \
	X(shared_ptr<ContactKind>, kind, shared_ptr<ContactKind>(), "Kind of the contact (shared parameters) [-]")                                           \
	X(int, kindId, 0, "kind.kindId, copied for fast queries (0 MORTAR, 1 ITZ, 2 AGG by convention) [-]")                                               \
	X(Real, area, 0.0, "Contact facet area A_c (Laguerre facet length x thickness b) [m2]")                                                             \
	X(Real, length, 0.0, "Centre distance L of the stress-free configuration; kn = E A / L [m]")                                                         \
	X(Real, swellDispInf, -1.0, "Per-contact ultimate swelling displacement d_inf; < 0: the kind's ContactKind.swellDispInf [m]")                      \
	X(Real, uRef, 0.0, "Normal opening (-penetrationDepth) at which the committed force was reached: the stress-free opening at "                       \
	                   "creation, then the converged opening of each physical step [m]")                                                                   \
	X(bool, broken, false, "Broken in the current iteration (committed or during this step) [-]")                                                       \
	X(int, failureMode, 0, "How it broke: 0 intact, 1 tension, 2 shear [-]")                                                                            \
	X(Real, Fn, 0.0, "Transmitted normal force, tension positive [N]")                                                                                  \
	X(Real, Fs, 0.0, "Transmitted shear force along the 2D tangent ez x normal [N]")                                                                    \
	X(Real, FnHat, 0.0, "Unclamped normal force; > 0 on a broken contact measures how far its crack is open [N]")                                       \
	X(bool, committedBroken, false, "Broken at the end of the last converged step [-]")                                                                 \
	X(int, committedMode, 0, "failureMode at the end of the last converged step [-]")                                                                   \
	X(Real, committedFn, 0.0, "Normal force at the end of the last converged step [N]")                                                                 \
	X(Real, committedFs, 0.0, "Shear force at the end of the last converged step [N]")                                                                  \
	X(Real, committedFnHat, 0.0, "Unclamped normal force at the end of the last converged step [N]")                                                   \
	X(std::vector<Real>, gamma, std::vector<Real>(), "Hidden Kelvin-chain strains, normal units then shear units (empty unless viscoelastic) [-]")    \
	X(long, stepSerial, -1, "Physical step the step data below belong to (ContactKind.stepSerial) [-]")                                              \
	X(Real, duOffsetN, 0.0, "Inelastic + swelling normal displacement increment of the current step (opening > 0) [m]")                              \
	X(Real, duOffsetS, 0.0, "Inelastic shear displacement increment of the current step [m]")                                                        \
	X(Real, shearHatX, 0.0, "Unclamped shear force vector of the current iteration, x [N]")                                                           \
	X(Real, shearHatY, 0.0, "Unclamped shear force vector of the current iteration, y [N]")                                                           \
	X(Real, shearHatZ, 0.0, "Unclamped shear force vector of the current iteration, z [N]")                                                           \
	X(Real, uTrial, 0.0, "Normal opening in the current iteration [m]")
	SWELLDEM_CLASS(SwellPhys, FrictPhys,
	               "Concrete contact of swelldem: aging viscoelastic (B3, solidification theory), swelling (Larive) and brittle. "
	               "Forces follow YADE's FrictPhys convention (normalForce, shearForce vectors) and are mirrored as signed "
	               "scalars Fn (tension positive) and Fs.",
	               SWELLDEM_SWELL_PHYS_ATTRS)
	SwellPhys() { createIndex(); }
	virtual ~SwellPhys() { }
	void postLoad() { }
	template <class C> static void pyMethods(C& cls)
	{
		cls.add_property("kindName", &SwellPhys::kindName, "Name of the contact's kind [-]");
		cls.add_property("swellingDispInf", &SwellPhys::effectiveSwellDispInf, "Ultimate swelling displacement in force (own or the kind's) [m]");
		cls.add_property("fnMax", &SwellPhys::fnMax, "Tensile strength of the contact f_t A (inf when damage is off) [N]");
	}
	string kindName() const { return kind ? kind->name : string(); }
	Real   effectiveSwellDispInf() const { return swellDispInf >= 0 ? swellDispInf : (kind ? kind->swellDispInf : 0.0); }
	Real   fnMax() const { return kind && kind->damage ? kind->tensileStrength * area : std::numeric_limits<Real>::infinity(); }
	swelldem::core::ContactGeometry geometry() const;
	// Copies between this object and the core's ContactState (at step set-up and commit only).
	void toCore(swelldem::core::ContactState& s) const;
	void fromCore(const swelldem::core::ContactState& s);
	SWELLDEM_CLASS_INDEX(SwellPhys, FrictPhys)
};

} // namespace yade
