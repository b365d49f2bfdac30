// SPDX-License-Identifier: GPL-2.0-or-later
#include "Law2_ScGeom_SwellPhys_AgingSwelling.hpp"
#include "core/BrittleContact.hpp"
#include <algorithm>
#include <cmath>

namespace yade {
namespace core = swelldem::core;

namespace {
	// The 2D tangent: the scene lies in the plane z = 0.
	Vector3r tangentOf(const Vector3r& n) { return Vector3r(-n[1], n[0], 0); }
	core::ContactState& scratchState()
	{
		thread_local core::ContactState s; // reused: no allocation per contact once warm
		return s;
	}
}

void Law2_ScGeom_SwellPhys_AgingSwelling::beginContactStep(SwellPhys& p, const Vector3r& normal)
{
	ContactKind&      kind = *p.kind;
	core::ContactLaw& law  = kind.law();
	if (p.gamma.size() != law.hiddenStateSize()) {
		// The chain is sized when the integrator prepares the kinds; a contact without history
		// (nothing committed yet) takes the new size, one with history cannot.
		const bool history = p.committedFn != 0 || p.committedFs != 0 || std::any_of(p.gamma.begin(), p.gamma.end(), [](Real g) { return g != 0; });
		if (history)
			throw std::runtime_error("swelldem: contact of kind " + kind.name + " has " + std::to_string(p.gamma.size())
			                         + " hidden creep variables, its kind now needs " + std::to_string(law.hiddenStateSize())
			                         + " (the kind's Kelvin chain changed during the run)");
		p.gamma.assign(law.hiddenStateSize(), 0.0);
	}
	core::ContactState& s = scratchState();
	p.toCore(s);
	law.beginContactStep(p.geometry(), s);
	p.fromCore(s);
	p.FnHat = p.committedFnHat;
	// The step's constant shear offset enters the incremental shear vector once.
	Vector3r sh(p.shearHatX, p.shearHatY, p.shearHatZ);
	sh += p.ks * p.duOffsetS * tangentOf(normal);
	p.shearHatX = sh[0], p.shearHatY = sh[1], p.shearHatZ = sh[2];
	p.stepSerial = kind.stepSerial;
}

void Law2_ScGeom_SwellPhys_AgingSwelling::commit(SwellPhys& p)
{
	core::ContactLaw&   law = p.kind->law();
	core::ContactState& s   = scratchState();
	p.toCore(s);
	law.commit(p.geometry(), s);
	p.fromCore(s);
	p.uRef = p.uTrial;
}

bool Law2_ScGeom_SwellPhys_AgingSwelling::breakIfOverloaded(SwellPhys& p, Real FnHat, Real shearMagnitude)
{
	if (p.broken) return false;
	const core::BrittleStrength& strength = p.kind->law().params().strength;
	if (!strength.damage) return false;
	const core::FailureMode mode = core::BrittleContact::check(strength, p.area, FnHat, shearMagnitude);
	if (mode == core::FailureMode::None) return false;
	p.broken      = true;
	p.failureMode = int(mode);
#pragma omp atomic
	++p.kind->breakEvents;
	return true;
}

bool Law2_ScGeom_SwellPhys_AgingSwelling::go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I)
{
	ScGeom*    geom = static_cast<ScGeom*>(ig.get());
	SwellPhys* p    = static_cast<SwellPhys*>(ip.get());
	if (p->stepSerial != p->kind->stepSerial) beginContactStep(*p, geom->normal);

	// Normal: Fn = Fn_committed + kn'' (du - du'' - du_sw), opening positive, tension positive.
	const Real u  = -geom->penetrationDepth;
	p->uTrial     = u;
	const Real FnHat = p->committedFnHat + p->kn * ((u - p->uRef) - p->duOffsetN);
	// Shear: YADE's incremental vector, carried into the current contact plane.
	Vector3r sh(p->shearHatX, p->shearHatY, p->shearHatZ);
	geom->rotate(sh);
	sh -= p->ks * geom->shearIncrement();
	const Real FsTrial = -sh.dot(tangentOf(geom->normal));

	Real Fn = FnHat, Fs = FsTrial;
	if (!p->kind->breaksAtEquilibrium && breakIfOverloaded(*p, FnHat, std::abs(FsTrial))) {
#pragma omp atomic
		++nBreaks;
	}
	if (p->broken) {
		const core::BrittleStrength& strength = p->kind->law().params().strength;
		core::BrittleContact::brokenForces(strength, FnHat, FsTrial, Fn, Fs);
		if (FsTrial != 0) sh *= Fs / FsTrial; // slip beyond the Coulomb cone is permanent
	}
	p->FnHat     = FnHat;
	p->Fn        = Fn;
	p->Fs        = Fs;
	p->shearHatX = sh[0], p->shearHatY = sh[1], p->shearHatZ = sh[2];
	p->normalForce = -Fn * geom->normal;
	p->shearForce  = sh;

	// Same force and torque application as Law2_ScGeom_FrictPhys_CundallStrack with spherical bodies.
	const Vector3r force = -p->normalForce - p->shearForce;
	scene->forces.addForce(I->getId1(), force);
	scene->forces.addForce(I->getId2(), -force);
	scene->forces.addTorque(I->getId1(), (geom->radius1 - 0.5 * geom->penetrationDepth) * geom->normal.cross(force));
	scene->forces.addTorque(I->getId2(), (geom->radius2 - 0.5 * geom->penetrationDepth) * geom->normal.cross(force));
	return true;
}

} // namespace yade
