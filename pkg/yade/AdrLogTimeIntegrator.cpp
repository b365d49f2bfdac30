// SPDX-License-Identifier: GPL-2.0-or-later
#include "AdrLogTimeIntegrator.hpp"
#include "core/LogTimes.hpp"
#include "core/Validate.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace yade {
namespace core = swelldem::core;

namespace {
	const unsigned kNeed2D = State::DOF_Z | State::DOF_RX | State::DOF_RY;
	// Below this many discs a loop is cheaper than waking OpenMP's threads.
	const long kParallelBodies = 4000;
	string         num(double v)
	{
		std::ostringstream o;
		o.precision(4);
		o << v;
		return o.str();
	}
}

void AdrLogTimeIntegrator::postLoad()
{
	core::requirePositive("AdrLogTimeIntegrator.tStart [day]", tStart);
	core::requireGreater("AdrLogTimeIntegrator.tEnd [day]", tEnd, "tStart", tStart);
	core::requirePositive("AdrLogTimeIntegrator.stepsPerDecade", stepsPerDecade);
	core::requireOpenInterval("AdrLogTimeIntegrator.tolerance", tolerance, 0, 1);
	core::require(minIterations >= 1, "AdrLogTimeIntegrator.minIterations", minIterations, ">= 1");
	core::require(maxIterations >= minIterations, "AdrLogTimeIntegrator.maxIterations", maxIterations, ">= minIterations");
	core::require(massSafety >= 1, "AdrLogTimeIntegrator.massSafety", massSafety, ">= 1");
	core::requireOpenInterval("AdrLogTimeIntegrator.maxDamping", maxDamping, 0, 2);
	core::requirePositive("AdrLogTimeIntegrator.divergenceRatio", divergenceRatio);
	core::require(colliderPeriod >= 1, "AdrLogTimeIntegrator.colliderPeriod", colliderPeriod, ">= 1");
	core::requireOpenInterval("AdrLogTimeIntegrator.relativeForceFloor", relativeForceFloor, 0, 1);
	sessionStart = std::chrono::steady_clock::now();
}

double AdrLogTimeIntegrator::wallNow() const
{
	return wallBefore + std::chrono::duration<double>(std::chrono::steady_clock::now() - sessionStart).count();
}

void AdrLogTimeIntegrator::fail(const string& why) const
{
	std::ostringstream o;
	o << "swelldem: AdrLogTimeIntegrator stopped at physical step " << step << "/" << nSteps() << " (t = " << num(step > 0 ? times[step] : tStart)
	  << " d), ADR iteration " << iterInStep << " of the step (O.iter " << scene->iter << "): " << why
	  << ". The scene is left as it is; results written so far are kept.";
	throw std::runtime_error(o.str());
}

std::vector<ContactKind*> AdrLogTimeIntegrator::kindsInScene() const
{
	std::set<ContactKind*> kinds;
	const auto&            L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i)
		if (L[i]->isReal())
			if (auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get())) kinds.insert(p->kind.get());
	return std::vector<ContactKind*>(kinds.begin(), kinds.end());
}

void AdrLogTimeIntegrator::refreshKinds()
{
	kinds = kindsInScene();
	for (ContactKind* k : kinds)
		k->breaksAtEquilibrium = true;
}

long AdrLogTimeIntegrator::breakOverloaded()
{
	// Breaking in the transients of the fictitious dynamics would break contacts that the
	// equilibrium never loads beyond their strength (measured: twice the breaks of a slow
	// quasi-static loading). Checked here, at equilibrium, every overloaded contact breaks at once
	// and the step iterates again; what remains of the step size's effect is the load increment.
	long        n = 0;
	const auto& L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i) {
		if (!L[i]->isReal()) continue;
		auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get());
		// an intact contact carries Fs = its trial shear force
		if (p && Law2_ScGeom_SwellPhys_AgingSwelling::breakIfOverloaded(*p, p->FnHat, std::abs(p->Fs))) ++n;
	}
	return n;
}

long AdrLogTimeIntegrator::breakEvents() const
{
	long n = 0;
	for (ContactKind* k : kinds)
		n += k->breakEvents;
	return n;
}

void AdrLogTimeIntegrator::controlCollider()
{
	// Bonded contacts exist from the start; the collider only has to find contacts made later,
	// which a quasi-static run may find a few iterations late: run it once every colliderPeriod
	// iterations and at the start of each physical step.
	if (colliderPeriod <= 1) return;
	for (const auto& e : scene->engines)
		if (e && e->label == colliderLabel) e->dead = !(iterInStep == 0 || totalIterations % colliderPeriod == 0);
}

void AdrLogTimeIntegrator::initialize()
{
	postLoad();
	for (const auto& b : scene->bodies->body)
		if (b && (b->state->blockedDOFs & kNeed2D) != kNeed2D)
			throw std::invalid_argument("swelldem: AdrLogTimeIntegrator is a 2D solver: body " + std::to_string(b->id)
			                            + " must have z translation and x, y rotations blocked (State.blockedDOFs containing 'zXY')");
	times = core::logTimes(tStart, tEnd, stepsPerDecade, std::vector<double>(extraTimes.begin(), extraTimes.end()));
	const double shortest = times[1] - times[0];
	for (ContactKind* k : kindsInScene())
		k->prepare(shortest, tEnd - tStart);
	const size_t n = scene->bodies->body.size();
	initialPos.assign(2 * n, 0.0);
	for (const auto& b : scene->bodies->body)
		if (b) {
			initialPos[2 * b->id]     = b->state->se3.position[0];
			initialPos[2 * b->id + 1] = b->state->se3.position[1];
			b->state->vel             = Vector3r::Zero();
			b->state->angVel          = Vector3r::Zero();
		}
	prevForce.assign(3 * n, 0.0);
	scene->dt      = 1.0;
	step           = 1;
	physTime       = tStart;
	nContactsSeen  = -1;
	sessionStart   = std::chrono::steady_clock::now();
	wallBefore     = 0;
	refreshKinds();
	brokenSeen     = breakEvents();
	beginPhysicalStep();
	rebeginStep = false;
	if (verbose) {
		std::printf("swelldem: %d physical steps from %s to %s days (%s a decade), ADR tolerance %s\n", nSteps(), num(tStart).c_str(), num(tEnd).c_str(),
		            num(stepsPerDecade).c_str(), num(tolerance).c_str());
		std::fflush(stdout);
	}
}

void AdrLogTimeIntegrator::beginPhysicalStep()
{
	refreshKinds();
	for (ContactKind* k : kinds) {
		k->law().beginStep(times[step - 1], times[step]);
		++k->stepSerial;
	}
	iterInStep = 0;
	for (const auto& b : scene->bodies->body)
		if (b) b->state->vel = Vector3r::Zero(), b->state->angVel = Vector3r::Zero();
	std::fill(prevForce.begin(), prevForce.end(), 0.0);
}

void AdrLogTimeIntegrator::commitPhysicalStep()
{
	const auto& L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i)
		if (L[i]->isReal())
			if (auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get())) Law2_ScGeom_SwellPhys_AgingSwelling::commit(*p);
	physTime = times[step];
	stepIterations.push_back(iterInStep);
	stepUnbalanced.push_back(unbalanced);
	stepWall.push_back(wallNow());
	if (verbose) {
		const double el = wallNow(), left = el / step * (nSteps() - step);
		std::printf("swelldem: step %d/%d  t = %s d  ADR iterations %ld (total %ld)  unbalanced %.2e  elapsed %.1f s  left ~%.1f s\n", step, nSteps(),
		            num(physTime).c_str(), iterInStep, totalIterations, unbalanced, el, left);
		std::fflush(stdout);
	}
	if (step == nSteps()) {
		finished = true;
		for (const auto& b : scene->bodies->body)
			if (b) b->state->vel = Vector3r::Zero(), b->state->angVel = Vector3r::Zero();
		scene->stopAtIter = scene->iter + 1;
	} else {
		++step;
		beginPhysicalStep();
	}
	if (stepHook_) {
		PyGILState_STATE gil = PyGILState_Ensure();
		bool             ok  = true;
		try {
			(*stepHook_)();
		} catch (const boost::python::error_already_set&) {
			PyErr_Print();
			ok = false;
		}
		PyGILState_Release(gil);
		if (!ok) fail("the stepHook raised a Python exception (printed above)");
	}
}

AdrLogTimeIntegrator::~AdrLogTimeIntegrator()
{
	if (!stepHook_) return;
	if (Py_IsInitialized()) {
		PyGILState_STATE gil = PyGILState_Ensure();
		stepHook_.reset();
		PyGILState_Release(gil);
	} else
		stepHook_.release(); // the interpreter is gone: its objects with it
}

boost::python::object AdrLogTimeIntegrator::getStepHook() const { return stepHook_ ? *stepHook_ : boost::python::object(); }

void AdrLogTimeIntegrator::setStepHook(const boost::python::object& hook)
{
	if (hook.is_none()) {
		stepHook_.reset();
		return;
	}
	if (!PyCallable_Check(hook.ptr()))
		throw std::invalid_argument("AdrLogTimeIntegrator.stepHook = " + string(boost::python::extract<string>(boost::python::str(hook)))
		                            + " is out of range; allowed: a callable taking no arguments, or None");
	stepHook_ = std::make_unique<boost::python::object>(hook);
}

void AdrLogTimeIntegrator::computeMasses()
{
	// Gershgorin row sums of the contact stiffness in 2D: a contact's relative displacement is
	// B q with rows n = (-n, 0, n, 0) and t = (-t, -r1, t, -r2) over (u1, theta1, u2, theta2);
	// |K| row a <= sum_k k_k |B_ka| sum_b |B_kb|.
	const size_t n = scene->bodies->body.size();
	massX.assign(n, 0.0), massY.assign(n, 0.0), inertiaZ.assign(n, 0.0);
	const auto& L = scene->interactions->linIntrs;
	long        nReal = 0;
	for (size_t i = 0; i < scene->interactions->currSize; ++i) {
		const Interaction* I = L[i].get();
		if (!I->isReal()) continue;
		++nReal;
		const auto* g = static_cast<const ScGeom*>(I->geom.get());
		const auto* p = static_cast<const NormShearPhys*>(I->phys.get());
		const Vector3r& nn = g->normal;
		const Real      tx = -nn[1], ty = nn[0];
		const Real      r1 = g->radius1 - 0.5 * g->penetrationDepth, r2 = g->radius2 - 0.5 * g->penetrationDepth;
		const Real      rowN = 2 * (std::abs(nn[0]) + std::abs(nn[1])), rowT = 2 * (std::abs(tx) + std::abs(ty)) + r1 + r2;
		const Real      kn = std::abs(p->kn), ks = std::abs(p->ks);
		const Real      mx = kn * std::abs(nn[0]) * rowN + ks * std::abs(tx) * rowT;
		const Real      my = kn * std::abs(nn[1]) * rowN + ks * std::abs(ty) * rowT;
		for (int side = 0; side < 2; ++side) {
			const int  id = side == 0 ? I->id1 : I->id2;
			const Real r  = side == 0 ? r1 : r2;
			massX[id] += mx;
			massY[id] += my;
			inertiaZ[id] += ks * r * rowT;
		}
	}
	const Real f = 0.25 * scene->dt * scene->dt * massSafety;
	for (size_t i = 0; i < n; ++i)
		massX[i] *= f, massY[i] *= f, inertiaZ[i] *= f;
	nContactsSeen = nReal;
}

void AdrLogTimeIntegrator::action()
{
	if (times.empty()) {
		initialize();
		return; // contacts set themselves up for step 1 at the next iteration
	}
	if (finished) return;
	if (rebeginStep) {
		refreshKinds();
		for (ContactKind* k : kinds)
			k->law().beginStep(times[step - 1], times[step]);
		rebeginStep = false;
	}
	scene->forces.sync();
	++iterInStep;
	++totalIterations;

	// Unbalanced-force ratio, as YADE's unbalancedForce(): mean resultant on free bodies / mean contact force.
	const auto& bodies = scene->bodies->body;
	const long  nBodies = long(bodies.size());
	Real        sumRes = 0, sumContact = 0, sumKn = 0, posScale = 0;
	long        nFree = 0, nReal = 0, badBody = -1;
#pragma omp parallel for schedule(static) reduction(+ : sumRes, nFree) reduction(max : posScale) if (nBodies > kParallelBodies)
	for (long k = 0; k < nBodies; ++k) {
		const Body* b = bodies[k].get();
		if (!b || b->isClump()) continue;
		const State* s = b->state.get();
		if ((s->blockedDOFs & (State::DOF_X | State::DOF_Y)) == (State::DOF_X | State::DOF_Y)) continue;
		const Vector3r& f = scene->forces.getForce(b->id);
		if (!std::isfinite(f[0]) || !std::isfinite(f[1])) {
#pragma omp critical(swelldemBadBody)
			if (badBody < 0 || b->id < badBody) badBody = b->id;
			continue;
		}
		Real fx = (s->blockedDOFs & State::DOF_X) ? 0 : f[0], fy = (s->blockedDOFs & State::DOF_Y) ? 0 : f[1];
		sumRes += std::sqrt(fx * fx + fy * fy);
		posScale = std::max(posScale, s->se3.position.head<2>().cwiseAbs().maxCoeff());
		++nFree;
	}
	if (badBody >= 0) {
		const Vector3r& f = scene->forces.getForce(int(badBody));
		fail("non-finite force on body " + std::to_string(badBody) + " (" + num(f[0]) + ", " + num(f[1]) + ") N");
	}
	const auto& L     = scene->interactions->linIntrs;
	const long  nIntr = long(scene->interactions->currSize);
#pragma omp parallel for schedule(static) reduction(+ : nReal, sumContact, sumKn) if (nIntr > 2 * kParallelBodies)
	for (long i = 0; i < nIntr; ++i) {
		const Interaction* I = L[i].get();
		if (!I->isReal()) continue;
		++nReal;
		const auto* p = static_cast<const NormShearPhys*>(I->phys.get());
		Real        F = (p->normalForce + p->shearForce).norm();
		sumKn += std::abs(p->kn);
		// A contact that the step loads through its own offset (swelling, creep) counts at least
		// with that load: free swelling ends with zero contact forces, not with a zero ratio.
		if (const auto* sp = dynamic_cast<const SwellPhys*>(p)) F = std::max(F, std::abs(sp->kn * sp->duOffsetN) + std::abs(sp->ks * sp->duOffsetS));
		sumContact += F;
	}
	// Steps that load the contacts by almost nothing (late swelling) are judged against a floor,
	// a fraction of the largest mean contact force of the run, not against round-off.
	Real meanContact = nReal > 0 ? sumContact / nReal : 0;
	forceScaleMax    = std::max(forceScaleMax, meanContact);
	meanContact      = std::max(meanContact, relativeForceFloor * forceScaleMax);
	unbalanced       = (nFree == 0 || meanContact == 0) ? (sumRes == 0 ? 0.0 : std::numeric_limits<Real>::infinity())
	                                                    : (sumRes / nFree) / meanContact;
	if (!std::isfinite(sumContact)) fail("a contact force is not finite");

	// Below this residual positions cannot resolve a better equilibrium (their round-off times the
	// stiffness): a step loaded by next to nothing converges there instead of never.
	const bool atRoundOff = nReal > 0 && nFree > 0 && sumRes / nFree <= 256 * std::numeric_limits<Real>::epsilon() * posScale * sumKn / nReal;

	if (nReal != nContactsSeen) refreshKinds();
	const long breaks    = breakEvents();
	const bool newBreaks = breaks != brokenSeen;
	brokenSeen           = breaks;
	// A break leaves kn, ks (and so the Gershgorin bound) as they are: only new or lost contacts
	// and a new step's stiffness call for new masses.
	if (nReal != nContactsSeen || iterInStep == 1 || massX.size() != bodies.size()) computeMasses();

	if (iterInStep >= minIterations && !newBreaks && (unbalanced <= tolerance || atRoundOff) && breakOverloaded() == 0) {
		stepRoundOff.push_back(unbalanced > tolerance ? 1.0 : 0.0);
		commitPhysicalStep();
		controlCollider();
		return;
	}
	controlCollider();
	if (std::isnan(unbalanced) || unbalanced > divergenceRatio)
		fail("diverged: unbalanced-force ratio " + num(unbalanced) + " > divergenceRatio " + num(divergenceRatio));
	if (iterInStep >= maxIterations)
		fail("no equilibrium after maxIterations = " + std::to_string(maxIterations) + " ADR iterations (unbalanced-force ratio " + num(unbalanced)
		     + ", tolerance " + num(tolerance) + ")");

	// Damping from the Rayleigh quotient of the local diagonal stiffness estimate (Underwood).
	const Real dt = scene->dt;
	Real       num_ = 0, den = 0;
#pragma omp parallel for schedule(static) reduction(+ : num_, den) if (nBodies > kParallelBodies)
	for (long k = 0; k < nBodies; ++k) {
		const Body* b = bodies[k].get();
		if (!b) continue;
		const State*    s  = b->state.get();
		const int       id = b->id;
		const Vector3r& f  = scene->forces.getForce(id);
		const Real      x[2] = { s->se3.position[0] - initialPos[2 * id], s->se3.position[1] - initialPos[2 * id + 1] };
		const Real      m[2] = { massX[id], massY[id] };
		for (int d = 0; d < 2; ++d) {
			const Real v = s->vel[d];
			if (v == 0 || m[d] == 0) continue;
			const Real kLocal = -(f[d] - prevForce[3 * id + d]) / (dt * v);
			num_ += x[d] * kLocal * x[d];
			den += x[d] * m[d] * x[d];
		}
	}
	Real c = (num_ > 0 && den > 0) ? 2 * std::sqrt(num_ / den) : 0;
	c      = std::min(c, maxDamping / dt);
	damping = c * dt;

#pragma omp parallel for schedule(static) if (nBodies > kParallelBodies)
	for (long k = 0; k < nBodies; ++k) {
		const Body* b = bodies[k].get();
		if (!b) continue;
		State*          s  = b->state.get();
		const int       id = b->id;
		const Vector3r& f  = scene->forces.getForce(id);
		const Vector3r& t  = scene->forces.getTorque(id);
		prevForce[3 * id] = f[0], prevForce[3 * id + 1] = f[1], prevForce[3 * id + 2] = t[2];
		const Real m[2] = { massX[id], massY[id] };
		for (int d = 0; d < 2; ++d) {
			if ((s->blockedDOFs & (d == 0 ? State::DOF_X : State::DOF_Y)) || m[d] == 0) {
				s->vel[d] = 0;
				continue;
			}
			s->vel[d] = ((2 - c * dt) * s->vel[d] + 2 * dt * f[d] / m[d]) / (2 + c * dt);
			s->se3.position[d] += dt * s->vel[d];
		}
		if (!(s->blockedDOFs & State::DOF_RZ) && inertiaZ[id] > 0) {
			s->angVel[2] = ((2 - c * dt) * s->angVel[2] + 2 * dt * t[2] / inertiaZ[id]) / (2 + c * dt);
			s->se3.orientation = Quaternionr(Eigen::AngleAxis<Real>(dt * s->angVel[2], Vector3r::UnitZ())) * s->se3.orientation;
			s->se3.orientation.normalize();
		} else
			s->angVel[2] = 0;
	}
}

} // namespace yade
