// SPDX-License-Identifier: GPL-2.0-or-later
#include "LogTimeSolver.hpp"
#include "core/LogTimes.hpp"
#include "core/Validate.hpp"
#include "SparseSolver.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace yade {
namespace core = swelldem::core;

namespace {
	string num(double v)
	{
		std::ostringstream o;
		o.precision(4);
		o << v;
		return o.str();
	}
}

bool logTimeSolverPending(const Scene* scene)
{
	for (const auto& e : scene->engines)
		if (const auto* s = dynamic_cast<const LogTimeSolver*>(e.get()))
			if (s->times.empty()) return true;
	return false;
}

std::vector<Real> LogTimeSolver::plannedTimes() const
{
	const auto t = core::logTimes(tStart, tEnd, stepsPerDecade, std::vector<double>(extraTimes.begin(), extraTimes.end()));
	return std::vector<Real>(t.begin(), t.end());
}

void LogTimeSolver::postLoad()
{
	// The schedule's checks are the core's (one range each); the list itself is made at the start.
	core::logTimes(tStart, tEnd, stepsPerDecade, std::vector<double>(extraTimes.begin(), extraTimes.end()));
	core::requireOpenInterval(getClassName() + ".tolerance", tolerance, 0, 1);
	core::require(minIterations >= 1, getClassName() + ".minIterations", minIterations, ">= 1");
	core::require(maxIterations >= minIterations, getClassName() + ".maxIterations", maxIterations, ">= minIterations");
	core::requirePositive(getClassName() + ".divergenceRatio", divergenceRatio);
	core::require(colliderPeriod >= 1, getClassName() + ".colliderPeriod", colliderPeriod, ">= 1");
	core::requireOpenInterval(getClassName() + ".relativeForceFloor", relativeForceFloor, 0, 1);
	// The three spring lists are set one after the other: their lengths are compared at the start.
	for (size_t i = 0; i < springBodies.size(); ++i)
		core::require(springBodies[i] >= 0, getClassName() + ".springBodies[" + std::to_string(i) + "]", springBodies[i], ">= 0 (a body id)");
	for (size_t i = 0; i < springAxes.size(); ++i)
		core::require(springAxes[i] >= 0 && springAxes[i] <= 2, getClassName() + ".springAxes[" + std::to_string(i) + "]", springAxes[i],
		              "0 (x), 1 (y) or 2 (z, 3D)");
	for (size_t i = 0; i < springStiffness.size(); ++i)
		core::requireNonNegative(getClassName() + ".springStiffness[" + std::to_string(i) + "] [N/m]", springStiffness[i]);
	core::require(historyEvery >= 0, getClassName() + ".historyEvery", historyEvery, ">= 0 (0: no history)");
}

void LogTimeSolver::afterLoad()
{
	sessionStart = std::chrono::steady_clock::now();
	wallBefore   = stepWall.empty() ? 0.0 : stepWall.back();
	kindsStale   = true;
}

double LogTimeSolver::wallNow() const
{
	return wallBefore + std::chrono::duration<double>(std::chrono::steady_clock::now() - sessionStart).count();
}

void LogTimeSolver::fail(const string& why) const
{
	std::ostringstream o;
	o << "swelldem: " << getClassName() << " stopped at physical step " << step << "/" << nSteps() << " (t = "
	  << num(step > 0 && size_t(step) < times.size() ? times[step] : tStart) << " d), iteration " << iterInStep << " of the step (O.iter "
	  << scene->iter << "): " << why << ". The scene is left as it is; results written so far are kept.";
	throw std::runtime_error(o.str());
}

void LogTimeSolver::trackHeldBodies()
{
	const auto& bodies = scene->bodies->body;
	const int   nd     = nDim;
	if (heldPos.size() != size_t(nd) * bodies.size()) {
		heldPos.assign(size_t(nd) * bodies.size(), 0.0);
		for (const auto& b : bodies)
			if (b)
				for (int d = 0; d < nd; ++d) heldPos[nd * b->id + d] = b->state->se3.position[d];
		return;
	}
	for (const auto& b : bodies) {
		if (!b) continue;
		State* s = b->state.get();
		for (int d = 0; d < nd; ++d) {
			Real& was = heldPos[nd * b->id + d];
			if (s->blockedDOFs & kAxisDOF[d]) s->vel[d] = (s->se3.position[d] - was) / scene->dt;
			was = s->se3.position[d];
		}
	}
}

void LogTimeSolver::zeroVelocities(Scene* scene)
{
	for (const auto& b : scene->bodies->body)
		if (b) b->state->vel = Vector3r::Zero(), b->state->angVel = Vector3r::Zero();
}

void LogTimeSolver::findLaw()
{
	law2 = sceneLaw(scene, getClassName());
	law2->setLogTimeModes(shearFromStepStart);
}

void LogTimeSolver::refreshKinds()
{
	std::set<const ContactKind*> found;
	const auto&            L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i)
		if (L[i]->isReal())
			if (auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get())) found.insert(p->kind.get());
	kinds.assign(found.begin(), found.end());
}

long LogTimeSolver::breakOverloaded()
{
	// Breaking in the transients of the iterations would break contacts that the equilibrium never
	// loads beyond their strength (measured with the ADR: twice the breaks of a slow quasi-static
	// loading). Checked here, at equilibrium, every overloaded contact breaks at once and the step
	// iterates again; what remains of the step size's effect is the load increment.
	long        n = 0;
	const auto& L = scene->interactions->linIntrs;
	if (breakOneAtATime) {
		SwellPhys* worst = nullptr;
		Real       most  = 1;
		for (size_t i = 0; i < scene->interactions->currSize; ++i) {
			if (!L[i]->isReal()) continue;
			if (auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get())) {
				const Real r = law2->lawFor(*p->kind).overload(p->geometry(), p->state);
				if (r > most) most = r, worst = p;
			}
		}
		return worst && law2->breakIfOverloaded(*worst) ? 1 : 0;
	}
	for (size_t i = 0; i < scene->interactions->currSize; ++i) {
		if (!L[i]->isReal()) continue;
		if (auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get()))
			if (law2->breakIfOverloaded(*p)) ++n;
	}
	return n;
}

void LogTimeSolver::controlCollider()
{
	// Bonded contacts exist from the start; the collider only has to find contacts made later,
	// which a quasi-static run may find a few iterations late: run it once every colliderPeriod
	// iterations and at the start of each physical step.
	if (colliderPeriod <= 1) return;
	for (const auto& e : scene->engines)
		if (e && e->label == colliderLabel) e->dead = !(iterInStep == 0 || totalIterations % colliderPeriod == 0);
}

void LogTimeSolver::initialize()
{
	postLoad();
	// 2D: every body in the plane (z, x and y rotations blocked); 3D: no free body so held. A body
	// free to move along one axis at most (a platen, a held disc or sphere) belongs to either.
	long planar = -1, spatial = -1;
	for (const auto& b : scene->bodies->body) {
		if (!b) continue;
		const unsigned blocked = b->state->blockedDOFs;
		if (!(blocked & State::DOF_X) + !(blocked & State::DOF_Y) + !(blocked & State::DOF_Z) <= 1) continue;
		if ((blocked & kNeed2D) == kNeed2D) {
			if (planar < 0) planar = b->id;
		} else if (spatial < 0)
			spatial = b->id;
	}
	if (planar >= 0 && spatial >= 0)
		throw std::invalid_argument("swelldem: " + getClassName() + " cannot start: body " + std::to_string(planar)
		                            + " is a disc of a 2D section (State.blockedDOFs containing 'zXY') and body " + std::to_string(spatial)
		                            + " a sphere free out of the plane; allowed: all discs (2D) or all spheres (3D)");
	nDim = spatial >= 0 ? 3 : 2;
	checkMpiRanks(); // here, not in postLoad: the linear solver is often set after the solver is made
	requireContactKinds(scene, getClassName());
	findLaw();
	times = core::logTimes(tStart, tEnd, stepsPerDecade, std::vector<double>(extraTimes.begin(), extraTimes.end()));
	zeroVelocities(scene);
	scene->dt    = 1.0;
	step         = 1;
	physTime     = tStart;
	nRealSeen    = -1;
	sessionStart = std::chrono::steady_clock::now();
	wallBefore   = 0;
	refreshKinds();
	brokenSeen = law2->nBreaks;
	heldPos.clear();
	trackHeldBodies();
	const string n = std::to_string(springBodies.size());
	core::require(springAxes.size() == springBodies.size(), getClassName() + ".springAxes (length)", double(springAxes.size()), n + ", as springBodies");
	core::require(springStiffness.size() == springBodies.size(), getClassName() + ".springStiffness (length)", double(springStiffness.size()),
	              n + ", as springBodies");
	springAnchors.clear();
	for (size_t i = 0; i < springBodies.size(); ++i) {
		const auto& B = scene->bodies->body;
		if (size_t(springBodies[i]) >= B.size() || !B[springBodies[i]])
			throw std::invalid_argument("swelldem: " + getClassName() + ".springBodies[" + std::to_string(i) + "] = " + std::to_string(springBodies[i])
			                            + " is not a body of the scene");
		if (springAxes[i] >= nDim)
			core::require(false, getClassName() + ".springAxes[" + std::to_string(i) + "]", springAxes[i], "0 (x) or 1 (y) in a 2D scene");
		springAnchors.push_back(B[springBodies[i]]->state->se3.position[springAxes[i]]);
	}
	if (verbose) {
		std::printf("swelldem: %s, %d physical steps from %s to %s days (%s a decade), tolerance %s\n", getClassName().c_str(), nSteps(),
		            num(tStart).c_str(), num(tEnd).c_str(), num(stepsPerDecade).c_str(), num(tolerance).c_str());
		std::fflush(stdout);
	}
	beginPhysicalStep();
	kindsStale = false;
}

void LogTimeSolver::checkMpiRanks() const
{
	if (const int ranks = swelldem::linalg::mpiRanks(); ranks > 1 && !(sharesRanks && sharesRanks()))
		throw std::invalid_argument("swelldem: " + getClassName() + " cannot " + (times.empty() ? "start" : "go on") + " on " + std::to_string(ranks)
		                            + " MPI ranks (mpirun): the ranks above 0 take part only in PETSc's linear solves; allowed under mpirun: "
		                              "ImplicitLogTimeSolver with linearSolver 'auto', 'petsc-gamg' or 'petsc-mumps'"
		                            + (times.empty() ? std::string()
		                                             : std::string(", and a run continued after O.load keeps the linear solver its first system took "
		                                                           "(ImplicitLogTimeSolver.linearSolverUsed)")));
}

void LogTimeSolver::beginPhysicalStep()
{
	refreshKinds();
	// Each kind's law is built for the whole analysis: its Kelvin chain spans the first step to the run's span.
	law2->laws.beginStep(kinds, times[1] - times[0], tEnd - tStart, times[step - 1], times[step]);
	iterInStep = 0;
	roundStart = 0;
	zeroVelocities(scene);
}

bool LogTimeSolver::startIteration()
{
	if (times.empty()) {
		initialize();
		return false; // contacts set themselves up for step 1 at the next iteration
	}
	if (finished) return false;
	const string err = takeFunctorError();
	if (!err.empty()) fail(err);
	if (kindsStale) { // the first iteration after O.load (a fresh run found both in initialize)
		checkMpiRanks();
		findLaw();
		refreshKinds();
		kindsStale = false;
	}
	applySprings();
	scene->forces.sync();
	++iterInStep;
	++totalIterations;
	return true;
}

void LogTimeSolver::applySprings()
{
	for (size_t i = 0; i < springBodies.size() && i < springAnchors.size(); ++i) {
		const int axis = springAxes[i];
		Vector3r  f    = Vector3r::Zero();
		f[axis]        = -springStiffness[i] * (scene->bodies->body[springBodies[i]]->state->se3.position[axis] - springAnchors[i]);
		scene->forces.addForce(springBodies[i], f);
	}
}

void LogTimeSolver::measureExternalScale(long nFree)
{
	// Loads not made by contacts (ForceEngine, O.forces.setPermF, ...) are the resultant force on a
	// body less its contacts' forces; measured once a step (they are constant within it).
	const auto&           bodies = scene->bodies->body;
	std::vector<Vector3r> contact(bodies.size(), Vector3r::Zero());
	const auto&           L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i) {
		const Interaction* I = L[i].get();
		if (!I->isReal()) continue;
		const auto*    p = static_cast<const NormShearPhys*>(I->phys.get());
		const Vector3r f = -p->normalForce - p->shearForce;
		contact[I->id1] += f;
		contact[I->id2] -= f;
	}
	Real           sum   = 0;
	const unsigned moves = nDim == 3 ? State::DOF_X | State::DOF_Y | State::DOF_Z : State::DOF_X | State::DOF_Y;
	for (const auto& b : bodies) {
		if (!b || b->isClump()) continue;
		const State* s = b->state.get();
		if ((s->blockedDOFs & moves) == moves) continue;
		const Vector3r e  = scene->forces.getForce(b->id) - contact[b->id];
		const Real     e2 = ((s->blockedDOFs & State::DOF_X) ? 0 : e[0] * e[0]) + ((s->blockedDOFs & State::DOF_Y) ? 0 : e[1] * e[1]);
		sum += std::sqrt(nDim == 3 && !(s->blockedDOFs & State::DOF_Z) ? e2 + e[2] * e[2] : e2);
	}
	externalScale = nFree > 0 ? sum / nFree : 0;
}

LogTimeSolver::Balance LogTimeSolver::measureBalance()
{
	// Unbalanced-force ratio, as YADE's unbalancedForce(): mean resultant on free bodies / mean contact force.
	const auto& bodies  = scene->bodies->body;
	const long  nBodies = long(bodies.size());
	Real           sumRes = 0, sumContact = 0, sumKn = 0, posScale = 0;
	long           nFree = 0, nReal = 0, badBody = -1;
	const bool     threeD = nDim == 3;
	const unsigned moves  = threeD ? State::DOF_X | State::DOF_Y | State::DOF_Z : State::DOF_X | State::DOF_Y;
#pragma omp parallel for schedule(static) reduction(+ : sumRes, nFree) reduction(max : posScale) if (nBodies > kParallelBodies)
	for (long k = 0; k < nBodies; ++k) {
		const Body* b = bodies[k].get();
		if (!b || b->isClump()) continue;
		const State* s = b->state.get();
		if ((s->blockedDOFs & moves) == moves) continue;
		const Vector3r& f = scene->forces.getForce(b->id);
		if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || (threeD && !std::isfinite(f[2]))) {
#pragma omp critical(swelldemBadBody)
			if (badBody < 0 || b->id < badBody) badBody = b->id;
			continue;
		}
		Real fx = (s->blockedDOFs & State::DOF_X) ? 0 : f[0], fy = (s->blockedDOFs & State::DOF_Y) ? 0 : f[1];
		if (threeD) {
			const Real fz = (s->blockedDOFs & State::DOF_Z) ? 0 : f[2];
			sumRes += std::sqrt(fx * fx + fy * fy + fz * fz);
			posScale = std::max(posScale, s->se3.position.cwiseAbs().maxCoeff());
		} else {
			sumRes += std::sqrt(fx * fx + fy * fy);
			posScale = std::max(posScale, s->se3.position.head<2>().cwiseAbs().maxCoeff());
		}
		++nFree;
	}
	if (badBody >= 0) {
		const Vector3r& f = scene->forces.getForce(int(badBody));
		fail("non-finite force on body " + std::to_string(badBody) + " (" + num(f[0]) + ", " + num(f[1]) + (threeD ? ", " + num(f[2]) : string())
		     + ") N");
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
		if (const auto* sp = dynamic_cast<const SwellPhys*>(p))
			F = std::max(F, std::abs(sp->state.kn * sp->state.duOffsetN) + std::abs(sp->state.ks * sp->state.duOffsetS)
			                    + std::abs(sp->state.ks * sp->state.duOffsetS2));
		sumContact += F;
	}
	if (!std::isfinite(sumContact)) fail("a contact force is not finite");
	if (iterInStep == 1) measureExternalScale(nFree);
	// Steps that load the contacts by almost nothing (late swelling) are judged against a floor,
	// a fraction of the largest mean contact force of the run, not against round-off.
	Real meanContact = nReal > 0 ? sumContact / nReal : 0;
	forceScaleMax    = std::max(forceScaleMax, meanContact);
	meanContact      = std::max({ meanContact, relativeForceFloor * forceScaleMax, externalScale });
	Balance b;
	b.nReal = nReal;
	b.ratio = (nFree == 0 || meanContact == 0) ? (sumRes == 0 ? 0.0 : std::numeric_limits<Real>::infinity()) : (sumRes / nFree) / meanContact;
	// Below this residual positions cannot resolve a better equilibrium (their round-off times the
	// stiffness): a step loaded by next to nothing converges there instead of never.
	const Real floor = nReal > 0 ? 256 * std::numeric_limits<Real>::epsilon() * posScale * sumKn / nReal : 0;
	b.atRoundOff     = nReal > 0 && nFree > 0 && sumRes / nFree <= floor;
	b.roundOff       = meanContact > 0 ? floor / meanContact : 0;
	unbalanced   = b.ratio;
	// Each step's first iteration marks where its load enters, the regular records show the decay,
	// the converged iteration (commitPhysicalStep) where it ends.
	if (historyEvery > 0 && (iterInStep == 1 || totalIterations % historyEvery == 0)) recordHistory();
	if (nReal != nRealSeen) {
		refreshKinds();
		nRealSeen = nReal;
	}
	return b;
}

LogTimeSolver::StepOutcome LogTimeSolver::settleStep(const Balance& b, bool converged)
{
	const long breaks    = law2->nBreaks;
	const bool newBreaks = breaks != brokenSeen;
	brokenSeen           = breaks;
	StepOutcome out      = StepOutcome::Continue;
	if (verbose) longStepLine(b);
	if (iterInStep >= minIterations && !newBreaks && converged) {
		if (breakOverloaded() == 0) {
			stepRoundOff.push_back(b.ratio > tolerance ? 1.0 : 0.0);
			stepRoundOffRatio.push_back(b.roundOff);
			if (beforeCommit) beforeCommit();
			commitPhysicalStep();
			out = StepOutcome::Committed;
		} else {
			out        = StepOutcome::Broke;
			roundStart = iterInStep;
		}
	}
	controlCollider();
	if (out == StepOutcome::Committed) return out;
	if (std::isnan(b.ratio) || b.ratio > divergenceRatio)
		fail("diverged: unbalanced-force ratio " + num(b.ratio) + " > divergenceRatio " + num(divergenceRatio));
	if (iterInStep - roundStart >= maxIterations)
		fail("no equilibrium after maxIterations = " + std::to_string(maxIterations) + " iterations" + (roundStart > 0 ? " since the last breaks" : "")
		     + " (unbalanced-force ratio " + num(b.ratio) + ", tolerance " + num(tolerance) + ")"
		     + (progressDetail ? "; in this step" + progressDetail() : std::string()));
	return out;
}

void LogTimeSolver::longStepLine(const Balance& b)
{
	// A step that runs long (a cracking step, a fallback to relaxation) says every 30 s where it is,
	// so that a run is never silent for minutes; what is left cannot be estimated until it settles.
	constexpr double every = 30.0;
	const double     el    = wallNow();
	const double     start = stepWall.empty() ? 0.0 : stepWall.back();
	if (iterInStep <= 1) longStepShown = 0;
	if (el - start < every || el - std::max(longStepShown, start) < every) return;
	longStepShown = el;
	std::printf("swelldem: step %d/%d  t = %s to %s d  still iterating: %ld %s iterations%s so far, unbalanced %.2e (tolerance %.0e), "
	            "%.0f s in this step, elapsed %.1f s; left: unknown until the step settles\n",
	            step, nSteps(), num(times[step - 1]).c_str(), num(times[step]).c_str(), iterInStep, iterationName,
	            (progressDetail ? progressDetail() : std::string()).c_str(), b.ratio, tolerance, el - start, el);
	std::fflush(stdout);
}

void LogTimeSolver::progressLine() const
{
	// The steps' cost is not uniform: cracking steps take many times the others. The estimate is the
	// remaining steps at the larger of the mean step so far and the last step, so that it grows as
	// soon as cracking starts instead of trailing it.
	const double el   = wallNow();
	const double last = stepWall.size() >= 2 ? stepWall.back() - stepWall[stepWall.size() - 2] : el;
	const double left = std::max(el / step, last) * (nSteps() - step);
	// A step that ended above the tolerance ended at the positions' round-off, or (the implicit
	// solver) was settled by its relaxation's looser tolerances: say which, and where round-off lies.
	char reached[128] = "";
	if (!stepRoundOff.empty() && stepRoundOff.back() > 0 && !stepRoundOffRatio.empty()) {
		if (unbalanced <= stepRoundOffRatio.back())
			std::snprintf(reached, sizeof reached, " (at round-off: limit %.1e, tolerance %.0e)", stepRoundOffRatio.back(), tolerance);
		else
			std::snprintf(reached, sizeof reached, " (above the tolerance %.0e, settled by relaxation; round-off limit %.1e)", tolerance,
			              stepRoundOffRatio.back());
	}
	std::printf("swelldem: step %d/%d  t = %s d  %s iterations %ld%s (total %ld)  unbalanced %.2e%s  elapsed %.1f s  left ~%.1f s\n", step,
	            nSteps(), num(physTime).c_str(), iterationName, iterInStep, (progressDetail ? progressDetail() : std::string()).c_str(), totalIterations,
	            unbalanced, reached, el, left);
	std::fflush(stdout);
}

void LogTimeSolver::commitPhysicalStep()
{
	const auto& L = scene->interactions->linIntrs;
	for (size_t i = 0; i < scene->interactions->currSize; ++i)
		if (L[i]->isReal())
			if (auto* p = dynamic_cast<SwellPhys*>(L[i]->phys.get())) law2->commit(*p);
	physTime = times[step];
	stepIterations.push_back(iterInStep);
	stepUnbalanced.push_back(unbalanced);
	stepWall.push_back(wallNow());
	if (historyEvery > 0 && (historyIteration.empty() || historyIteration.back() != Real(totalIterations))) recordHistory();
	if (verbose) progressLine();
	if (step == nSteps()) {
		finished = true;
		if (verbose) {
			std::printf("swelldem: finished: %d physical steps to t = %s d, %ld %s iterations, %.1f s\n", nSteps(), num(physTime).c_str(),
			            totalIterations, iterationName, wallNow());
			std::fflush(stdout);
		}
		zeroVelocities(scene);
		scene->stopAtIter = scene->iter + 1;
	} else {
		++step;
		beginPhysicalStep();
	}
	runStepHook();
}

void LogTimeSolver::recordHistory()
{
	historyIteration.push_back(Real(totalIterations));
	historyUnbalanced.push_back(unbalanced);
}

void LogTimeSolver::runStepHook()
{
	if (!stepHook_) return;
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

LogTimeSolver::~LogTimeSolver()
{
	if (!stepHook_) return;
	if (Py_IsInitialized()) {
		PyGILState_STATE gil = PyGILState_Ensure();
		stepHook_.reset();
		PyGILState_Release(gil);
	} else
		stepHook_.release(); // the interpreter is gone, and its objects with it
}

boost::python::object LogTimeSolver::getStepHook() const { return stepHook_ ? *stepHook_ : boost::python::object(); }

void LogTimeSolver::setStepHook(const boost::python::object& hook)
{
	if (hook.is_none()) {
		stepHook_.reset();
		return;
	}
	if (!PyCallable_Check(hook.ptr()))
		throw std::invalid_argument(getClassName() + ".stepHook = " + string(boost::python::extract<string>(boost::python::str(hook)))
		                            + " is out of range; allowed: a callable taking no arguments, or None");
	stepHook_ = std::make_unique<boost::python::object>(hook);
}

void LogTimeSolver::action() { fail("LogTimeSolver is the base of the log-time solvers; use AdrLogTimeIntegrator or ImplicitLogTimeSolver"); }

} // namespace yade
