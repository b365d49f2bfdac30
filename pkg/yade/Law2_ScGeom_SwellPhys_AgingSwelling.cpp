// SPDX-License-Identifier: GPL-2.0-or-later
#include "Law2_ScGeom_SwellPhys_AgingSwelling.hpp"
#include "SceneFunctors.hpp"

namespace yade {
namespace core = swelldem::core;

namespace {
	// The 2D tangent: the scene lies in the plane z = 0.
	Vector3r tangentOf(const Vector3r& n) { return Vector3r(-n[1], n[0], 0); }
}

void Law2_ScGeom_SwellPhys_AgingSwelling::beginContactStep(SwellPhys& p, const Vector3r& normal)
{
	core::ContactState& s = p.state;
	lawFor(*p.kind).beginContactStep(p.geometry(), s);
	p.kn = s.kn; // YADE's own members, for YADE's tools (time steppers, exporters)
	p.ks = s.ks;
	// The step's constant shear offset enters the incremental shear vector once.
	if (p.dim == 3) {
		const auto [t1, t2] = tangents(normal, p.frameAxis);
		p.shearForce += s.ks * (s.duOffsetS * t1 + s.duOffsetS2 * t2);
	} else
		p.shearForce += s.ks * s.duOffsetS * tangentOf(normal);
	p.stepSerial = window.serial;
}

void Law2_ScGeom_SwellPhys_AgingSwelling::setLogTimeModes(bool fromStepStart)
{
	breaksAtEquilibrium = true;
	shearFromStepStart  = fromStepStart;
}

void Law2_ScGeom_SwellPhys_AgingSwelling::commit(SwellPhys& p) { lawFor(*p.kind).commit(p.geometry(), p.state); }

bool Law2_ScGeom_SwellPhys_AgingSwelling::breakIfOverloaded(SwellPhys& p)
{
	if (!lawFor(*p.kind).breakIfOverloaded(p.geometry(), p.state)) return false;
#pragma omp atomic
	++nBreaks;
	return true;
}

int Law2_ScGeom_SwellPhys_AgingSwelling::chainSize(const shared_ptr<ContactKind>& kind)
{
	if (!kind) throw std::invalid_argument("swelldem: Law2_ScGeom_SwellPhys_AgingSwelling.chainSize(kind = None): allowed: a ContactKind");
	const core::ContactLaw& law = lawFor(*kind);
	return law.creep() ? int(law.creep()->size()) : 0;
}

Law2_ScGeom_SwellPhys_AgingSwelling* sceneLaw(Scene* scene, const string& solverName)
{
	const auto found = sceneFunctors<Law2_ScGeom_SwellPhys_AgingSwelling>(scene, "lawDispatcher");
	if (found.size() != 1)
		throw std::invalid_argument("swelldem: " + solverName + " cannot start: the scene's InteractionLoops hold "
		                            + std::to_string(found.size())
		                            + " Law2_ScGeom_SwellPhys_AgingSwelling functors; allowed: exactly one (it owns the run's laws of the kinds)");
	return found[0];
}

bool Law2_ScGeom_SwellPhys_AgingSwelling::go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I)
{
	auto*        geom = static_cast<ScGeom*>(ig.get());
	auto* p = static_cast<SwellPhys*>(ip.get());
	if (!p->kind) {
		// SwellPhys.kind refuses None, but the Ip2 leaves a contact it could not give a kind without
		// one (YADE aborts on a contact without physics): it carries no force and the solvers raise.
		recordFunctorError("SwellPhys.kind = None is out of range (contact of bodies " + std::to_string(I->getId1()) + " and "
		                   + std::to_string(I->getId2()) + "); allowed: a ContactKind; the contact carries no force");
		p->normalForce = p->shearForce = Vector3r::Zero();
		return true;
	}
	const ContactKind& kind = *p->kind;
	try {
		if (p->stepSerial != window.serial) {
			if (window.serial == 0 && logTimeSolverPending(scene)) {
				p->normalForce = p->shearForce = Vector3r::Zero();
				return true;
			}
			beginContactStep(*p, geom->normal);
		}
		core::ContactState& s = p->state;
		const bool          wasBroken = s.trial.broken;
		Vector3r            sh;
		const core::ContactForces* f;
		if (p->dim == 3) {
			// The shear's components on the contact's two tangents, with the same two paths as in 2D.
			const auto [t1, t2] = tangents(geom->normal, p->frameAxis);
			if (shearFromStepStart) {
				const Vector3r du = geom->shearIncrement();
				f = &lawFor(kind).updateFromStepStart(p->geometry(), s, -geom->penetrationDepth, du.dot(t1), du.dot(t2), !breaksAtEquilibrium);
			} else {
				sh = p->shearForce;
				geom->rotate(sh);
				sh -= s.ks * geom->shearIncrement();
				f = &lawFor(kind).update(p->geometry(), s, -geom->penetrationDepth, -sh.dot(t1), -sh.dot(t2), !breaksAtEquilibrium);
			}
			sh = -(f->Fs * t1 + f->Fs2 * t2);
		} else if (shearFromStepStart) {
			const Vector3r t = tangentOf(geom->normal);
			f  = &lawFor(kind).updateFromStepStart(p->geometry(), s, -geom->penetrationDepth, geom->shearIncrement().dot(t), !breaksAtEquilibrium);
			sh = -f->Fs * t;
		} else {
			const Vector3r t = tangentOf(geom->normal);
			// Shear: YADE's incremental vector, carried into the current contact plane.
			sh = p->shearForce;
			geom->rotate(sh);
			sh -= s.ks * geom->shearIncrement();
			const Real FsTrial = -sh.dot(t);
			f                  = &lawFor(kind).update(p->geometry(), s, -geom->penetrationDepth, FsTrial, !breaksAtEquilibrium);
			if (f->broken && FsTrial != 0) sh *= f->Fs / FsTrial; // slip beyond the Coulomb cone is permanent
		}
		if (f->broken && !wasBroken) {
#pragma omp atomic
			++nBreaks;
		}
		p->normalForce = -f->Fn * geom->normal;
		p->shearForce  = sh;
	} catch (const std::exception& e) {
		recordFunctorError(string(e.what()) + " (contact of bodies " + std::to_string(I->getId1()) + " and " + std::to_string(I->getId2()) + ")");
		p->normalForce = p->shearForce = Vector3r::Zero();
		return true;
	}
	// Same force and torque application as Law2_ScGeom_FrictPhys_CundallStrack with spherical bodies.
	const Vector3r force = -p->normalForce - p->shearForce;
	scene->forces.addForce(I->getId1(), force);
	scene->forces.addForce(I->getId2(), -force);
	scene->forces.addTorque(I->getId1(), (geom->radius1 - 0.5 * geom->penetrationDepth) * geom->normal.cross(force));
	scene->forces.addTorque(I->getId2(), (geom->radius2 - 0.5 * geom->penetrationDepth) * geom->normal.cross(force));
	return true;
}

} // namespace yade
