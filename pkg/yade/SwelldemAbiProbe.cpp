// SPDX-License-Identifier: GPL-2.0-or-later
#include "SwelldemAbiProbe.hpp"
#include <cstddef>

// offsetof on classes with virtual bases of YADE's kind is "conditionally supported"; GCC gives the
// real byte offset, which is exactly what the layout probe wants to report.
#pragma GCC diagnostic ignored "-Winvalid-offsetof"

namespace yade {
namespace bp = boost::python;

namespace {
	bp::tuple vec(const Vector3r& v) { return bp::make_tuple(v[0], v[1], v[2]); }
}

void SwelldemAbiProbe::action()
{
	++nCalls;
	lastIter = scene->iter;
	lastTime = scene->time;
	lastDt   = scene->dt;
	Real m = 0, ek = 0;
	for (const shared_ptr<Body>& b : scene->bodies->body) {
		if (!b) continue;
		m += b->state->mass;
		ek += 0.5 * b->state->mass * b->state->vel.squaredNorm();
	}
	totalMass     = m;
	kineticEnergy = ek;
}

bp::dict SwelldemAbiProbe::readScene() const
{
	bp::dict d;
	const Scene* s      = scene;
	d["dt"]             = s->dt;
	d["iter"]           = s->iter;
	d["time"]           = s->time;
	d["stopAtIter"]     = s->stopAtIter;
	d["isPeriodic"]     = s->isPeriodic;
	d["trackEnergy"]    = s->trackEnergy;
	d["selectedBody"]   = s->selectedBody;
	d["subStepping"]    = s->subStepping;
	bp::list tags;
	for (const string& t : s->tags)
		tags.append(t);
	d["tags"]           = tags;
	d["nEngines"]       = s->engines.size();
	d["nBodies"]        = s->bodies->body.size();
	d["nBodiesExported"] = s->bodies->size();
	d["nMaterials"]     = s->materials.size();
	d["nInteractions"]  = s->interactions->currSize;
	d["nLinIntrs"]      = s->interactions->linIntrs.size();
	d["forcesSyncCount"] = s->forces.syncCount;
	d["cellSet"]        = bool(s->cell);
	d["energySet"]      = bool(s->energy);
	return d;
}

bp::dict SwelldemAbiProbe::readBody(const shared_ptr<Body>& b)
{
	bp::dict     d;
	const State* st  = b->state.get();
	d["id"]          = b->id;
	d["groupMask"]   = b->groupMask;
	d["flags"]       = b->flags;
	d["clumpId"]     = b->clumpId;
	d["iterBorn"]    = b->iterBorn;
	d["timeBorn"]    = b->timeBorn;
	d["materialId"]  = b->material ? b->material->id : -999;
	d["nIntrs"]      = b->intrs.size();
	d["pos"]         = vec(st->se3.position);
	d["posRefOk"]    = (&st->pos == &st->se3.position);
	d["ori"]         = bp::make_tuple(st->se3.orientation.x(), st->se3.orientation.y(), st->se3.orientation.z(), st->se3.orientation.w());
	d["vel"]         = vec(st->vel);
	d["mass"]        = st->mass;
	d["angVel"]      = vec(st->angVel);
	d["angMom"]      = vec(st->angMom);
	d["inertia"]     = vec(st->inertia);
	d["refPos"]      = vec(st->refPos);
	d["blockedDOFs"] = st->blockedDOFs;
	d["isDamped"]    = st->isDamped;
	d["densityScaling"] = st->densityScaling;
	return d;
}

bp::dict SwelldemAbiProbe::readMaterial(const shared_ptr<Material>& m)
{
	bp::dict d;
	d["id"]      = m->id;
	d["label"]   = m->label;
	d["density"] = m->density;
	if (const FrictMat* f = dynamic_cast<const FrictMat*>(m.get())) {
		d["young"]         = f->young;
		d["poisson"]       = f->poisson;
		d["frictionAngle"] = f->frictionAngle;
	}
	return d;
}

bp::dict SwelldemAbiProbe::readInteraction(const shared_ptr<Interaction>& I)
{
	bp::dict d;
	d["id1"]          = I->id1;
	d["id2"]          = I->id2;
	d["iterMadeReal"] = I->iterMadeReal;
	d["iterBorn"]     = I->iterBorn;
	d["isReal"]       = I->isReal();
	d["isActive"]     = I->isActive;
	d["cellDist"]     = bp::make_tuple(I->cellDist[0], I->cellDist[1], I->cellDist[2]);
	d["lawFunctor"]   = I->functorCache.constLaw ? bp::object(reinterpret_cast<const Serializable*>(I->functorCache.constLaw.get())->getClassName())
	                                             : bp::object();
	if (const ScGeom* g = dynamic_cast<const ScGeom*>(I->geom.get())) {
		d["penetrationDepth"] = g->penetrationDepth;
		d["normal"]           = vec(g->normal);
		d["contactPoint"]     = vec(g->contactPoint);
		d["refR1"]            = g->refR1;
		d["refR2"]            = g->refR2;
		d["radius1"]          = g->radius1;
		d["radius2"]          = g->radius2;
		d["shearInc"]         = vec(g->shearInc);
	}
	if (const FrictPhys* p = dynamic_cast<const FrictPhys*>(I->phys.get())) {
		d["kn"]                     = p->kn;
		d["ks"]                     = p->ks;
		d["normalForce"]            = vec(p->normalForce);
		d["shearForce"]             = vec(p->shearForce);
		d["tangensOfFrictionAngle"] = p->tangensOfFrictionAngle;
	}
	return d;
}

bp::dict SwelldemAbiProbe::readEngine(const shared_ptr<Engine>& e)
{
	bp::dict d;
	d["dead"]       = e->dead;
	d["ompThreads"] = e->ompThreads;
	d["label"]      = e->label;
	d["execCount"]  = e->timingInfo.nExec;
	d["execTime"]   = e->timingInfo.nsec;
	d["hasScene"]   = e->scene != nullptr;
	return d;
}

bp::dict SwelldemAbiProbe::readFunctor(const shared_ptr<Functor>& f)
{
	bp::dict d;
	d["label"] = f->label;
	bp::list types;
	for (const string& t : f->getFunctorTypes())
		types.append(t);
	d["types"] = types;
	return d;
}

bp::dict SwelldemAbiProbe::declaredLayout()
{
	bp::dict d;
#define SWELLDEM_SIZE(C) d["sizeof " #C] = sizeof(C);
#define SWELLDEM_OFFSET(C, m) d[#C "::" #m] = offsetof(C, m);
	SWELLDEM_SIZE(Serializable)
	SWELLDEM_SIZE(FrictPhys)
	SWELLDEM_SIZE(ScGeom)
	SWELLDEM_SIZE(State)
	SWELLDEM_SIZE(FrictMat)
	SWELLDEM_SIZE(Body)
	SWELLDEM_SIZE(Interaction)
	SWELLDEM_SIZE(ForceContainer)
	SWELLDEM_SIZE(Scene)
	SWELLDEM_SIZE(Engine)
	SWELLDEM_SIZE(Functor)
	SWELLDEM_OFFSET(NormPhys, kn)
	SWELLDEM_OFFSET(NormPhys, normalForce)
	SWELLDEM_OFFSET(NormShearPhys, ks)
	SWELLDEM_OFFSET(NormShearPhys, shearForce)
	SWELLDEM_OFFSET(FrictPhys, tangensOfFrictionAngle)
	SWELLDEM_OFFSET(ScGeom, penetrationDepth)
	SWELLDEM_OFFSET(ScGeom, shearInc)
	SWELLDEM_OFFSET(State, se3)
	SWELLDEM_OFFSET(State, vel)
	SWELLDEM_OFFSET(State, blockedDOFs)
	SWELLDEM_OFFSET(State, densityScaling)
	SWELLDEM_OFFSET(Body, material)
	SWELLDEM_OFFSET(Body, intrs)
	SWELLDEM_OFFSET(Body, timeBorn)
	SWELLDEM_OFFSET(Interaction, id1)
	SWELLDEM_OFFSET(Interaction, phys)
	SWELLDEM_OFFSET(InteractionContainer, currSize)
	SWELLDEM_OFFSET(Scene, dt)
	SWELLDEM_OFFSET(Scene, time)
	SWELLDEM_OFFSET(Scene, bodies)
	SWELLDEM_OFFSET(Scene, interactions)
	SWELLDEM_OFFSET(Scene, cell)
	SWELLDEM_OFFSET(Engine, label)
	SWELLDEM_OFFSET(Functor, label)
#undef SWELLDEM_SIZE
#undef SWELLDEM_OFFSET
	return d;
}

} // namespace yade
