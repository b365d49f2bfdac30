// SPDX-License-Identifier: GPL-2.0-or-later
#include "AdrLogTimeIntegrator.hpp"
#include "core/Validate.hpp"
#include <cmath>

namespace yade {
namespace core = swelldem::core;

void AdrLogTimeIntegrator::postLoad()
{
	LogTimeSolver::postLoad();
	core::require(massSafety >= 1, "AdrLogTimeIntegrator.massSafety", massSafety, ">= 1");
	core::requireOpenInterval("AdrLogTimeIntegrator.maxDamping", maxDamping, 0, 2);
}

void AdrLogTimeIntegrator::start()
{
	const size_t n = scene->bodies->body.size();
	initialPos.assign(2 * n, 0.0);
	for (const auto& b : scene->bodies->body)
		if (b) {
			initialPos[2 * b->id]     = b->state->se3.position[0];
			initialPos[2 * b->id + 1] = b->state->se3.position[1];
		}
	prevForce.assign(3 * n, 0.0);
	nContactsSeen = -1;
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

Real AdrLogTimeIntegrator::dampingEstimate() const
{
	// Damping from the Rayleigh quotient of the local diagonal stiffness estimate (Underwood).
	const auto& bodies  = scene->bodies->body;
	const long  nBodies = long(bodies.size());
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
	return std::min(c, maxDamping / dt);
}

void AdrLogTimeIntegrator::leapfrog(Real c)
{
	const auto& bodies  = scene->bodies->body;
	const long  nBodies = long(bodies.size());
	const Real  dt      = scene->dt;
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

void AdrLogTimeIntegrator::action()
{
	const bool starting = times.empty();
	if (!startIteration()) {
		if (starting && !times.empty()) start();
		return;
	}
	struct Track {
		AdrLogTimeIntegrator* self;
		~Track() { self->trackHeldBodies(); }
	} track { this };
	const Balance b = measureBalance();
	// A break leaves kn, ks (and so the Gershgorin bound) as they are: only new or lost contacts
	// and a new step's stiffness call for new masses.
	if (b.nReal != nContactsSeen || iterInStep == 1 || massX.size() != scene->bodies->body.size()) computeMasses();
	if (settleStep(b, b.ratio <= tolerance || b.atRoundOff) == StepOutcome::Committed) {
		std::fill(prevForce.begin(), prevForce.end(), 0.0); // a new step starts from rest
		return;
	}
	const Real c = dampingEstimate();
	damping      = c * scene->dt;
	leapfrog(c);
}

} // namespace yade
