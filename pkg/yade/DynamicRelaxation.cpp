// SPDX-License-Identifier: GPL-2.0-or-later
#include "DynamicRelaxation.hpp"
#include <cmath>

namespace yade {

void DynamicRelaxation::start(const Scene* scene, int dim)
{
	nDim           = dim;
	const size_t n = scene->bodies->body.size();
	initialPos.assign(nDim * n, 0.0);
	for (const auto& b : scene->bodies->body)
		if (b)
			for (int d = 0; d < nDim; ++d) initialPos[nDim * b->id + d] = b->state->se3.position[d];
	prevForce.assign((nDim == 3 ? 6 : 3) * n, 0.0);
	nContactsSeen = -1;
}

void DynamicRelaxation::computeMasses(const Scene* scene, Real massSafety)
{
	// Gershgorin row sums of the contact stiffness: a contact's relative displacement is B q with,
	// in 2D, rows n = (-n, 0, n, 0) and t = (-t, -r1, t, -r2) over (u1, theta1, u2, theta2), and in
	// 3D the normal's row and, for each tangent t of the contact plane, (-t, -r1 (n x t), t, -r2 (n x t));
	// |K| row a <= sum_k k_k |B_ka| sum_b |B_kb|. In 3D any orthonormal pair of tangents gives a
	// bound; the axis least aligned with n makes the first.
	const bool   threeD = nDim == 3;
	const size_t n      = scene->bodies->body.size();
	massX.assign(n, 0.0), massY.assign(n, 0.0), inertiaZ.assign(n, 0.0);
	if (threeD) massZ.assign(n, 0.0), inertiaX.assign(n, 0.0), inertiaY.assign(n, 0.0);
	const auto& L = scene->interactions->linIntrs;
	long        nReal = 0;
	for (size_t i = 0; i < scene->interactions->currSize; ++i) {
		const Interaction* I = L[i].get();
		if (!I->isReal()) continue;
		++nReal;
		const auto*     g  = static_cast<const ScGeom*>(I->geom.get());
		const auto*     p  = static_cast<const NormShearPhys*>(I->phys.get());
		const Vector3r& nn = g->normal;
		const Real      r1 = g->radius1 - 0.5 * g->penetrationDepth, r2 = g->radius2 - 0.5 * g->penetrationDepth;
		const Real      kn = std::abs(p->kn), ks = std::abs(p->ks);
		if (threeD) {
			Eigen::Index k = 0;
			nn.cwiseAbs().minCoeff(&k);
			const Vector3r t1    = Vector3r::Unit(k).cross(nn).normalized();
			const Vector3r tt[2] = { t1, nn.cross(t1) };
			Vector3r       m = kn * 2 * nn.cwiseAbs().sum() * nn.cwiseAbs(), rot1 = Vector3r::Zero(), rot2 = Vector3r::Zero();
			for (const Vector3r& tk : tt) {
				const Vector3r lever = nn.cross(tk).cwiseAbs();
				const Real     rowT  = 2 * tk.cwiseAbs().sum() + (r1 + r2) * lever.sum();
				m += ks * rowT * tk.cwiseAbs();
				rot1 += ks * rowT * r1 * lever;
				rot2 += ks * rowT * r2 * lever;
			}
			for (int side = 0; side < 2; ++side) {
				const int       id  = side == 0 ? I->id1 : I->id2;
				const Vector3r& rot = side == 0 ? rot1 : rot2;
				massX[id] += m[0], massY[id] += m[1], massZ[id] += m[2];
				inertiaX[id] += rot[0], inertiaY[id] += rot[1], inertiaZ[id] += rot[2];
			}
			continue;
		}
		const Real tx = -nn[1], ty = nn[0];
		const Real rowN = 2 * (std::abs(nn[0]) + std::abs(nn[1])), rowT = 2 * (std::abs(tx) + std::abs(ty)) + r1 + r2;
		const Real mx = kn * std::abs(nn[0]) * rowN + ks * std::abs(tx) * rowT;
		const Real my = kn * std::abs(nn[1]) * rowN + ks * std::abs(ty) * rowT;
		for (int side = 0; side < 2; ++side) {
			const int  id = side == 0 ? I->id1 : I->id2;
			const Real r  = side == 0 ? r1 : r2;
			massX[id] += mx;
			massY[id] += my;
			inertiaZ[id] += ks * r * rowT;
		}
	}
	const Real f = 0.25 * scene->dt * scene->dt * massSafety;
	for (std::vector<Real>* a : { &massX, &massY, &massZ, &inertiaX, &inertiaY, &inertiaZ })
		for (Real& v : *a) v *= f; // the 3D arrays are empty in 2D
	nContactsSeen = nReal;
}

Real DynamicRelaxation::damping(Scene* scene, Real maxDamping) const
{
	// Damping from the Rayleigh quotient of the local diagonal stiffness estimate (Underwood), over
	// the translations.
	const auto&              bodies  = scene->bodies->body;
	const long               nBodies = long(bodies.size());
	const Real               dt      = scene->dt;
	const int                nd = nDim, perBody = nDim == 3 ? 6 : 3; // prevForce: forces then torques
	const std::vector<Real>* mass[3] = { &massX, &massY, &massZ };
	Real                     num_ = 0, den = 0;
#pragma omp parallel for schedule(static) reduction(+ : num_, den) if (nBodies > LogTimeSolver::kParallelBodies)
	for (long k = 0; k < nBodies; ++k) {
		const Body* b = bodies[k].get();
		if (!b) continue;
		const State*    s  = b->state.get();
		const int       id = b->id;
		const Vector3r& f  = scene->forces.getForce(id);
		for (int d = 0; d < nd; ++d) {
			const Real v = s->vel[d], m = (*mass[d])[id];
			if (v == 0 || m == 0) continue;
			const Real x      = s->se3.position[d] - initialPos[nd * id + d];
			const Real kLocal = -(f[d] - prevForce[perBody * id + d]) / (dt * v);
			num_ += x * kLocal * x;
			den += x * m * x;
		}
	}
	const Real c = (num_ > 0 && den > 0) ? 2 * std::sqrt(num_ / den) : 0;
	return std::min(c, maxDamping / dt);
}

void DynamicRelaxation::leapfrog(Scene* scene, Real c)
{
	const auto&              bodies  = scene->bodies->body;
	const long               nBodies = long(bodies.size());
	const Real               dt      = scene->dt;
	const bool               threeD  = nDim == 3;
	const std::vector<Real>* mass[3] = { &massX, &massY, &massZ };
	const std::vector<Real>* J[3]    = { &inertiaX, &inertiaY, &inertiaZ };
#pragma omp parallel for schedule(static) if (nBodies > LogTimeSolver::kParallelBodies)
	for (long k = 0; k < nBodies; ++k) {
		const Body* b = bodies[k].get();
		if (!b) continue;
		State*          s  = b->state.get();
		const int       id = b->id;
		const Vector3r& f  = scene->forces.getForce(id);
		const Vector3r& t  = scene->forces.getTorque(id);
		if (threeD)
			for (int d = 0; d < 3; ++d) prevForce[6 * id + d] = f[d], prevForce[6 * id + 3 + d] = t[d];
		else
			prevForce[3 * id] = f[0], prevForce[3 * id + 1] = f[1], prevForce[3 * id + 2] = t[2];
		for (int d = 0; d < nDim; ++d) {
			const Real m = (*mass[d])[id];
			if ((s->blockedDOFs & LogTimeSolver::kAxisDOF[d]) || m == 0) {
				s->vel[d] = 0;
				continue;
			}
			s->vel[d] = ((2 - c * dt) * s->vel[d] + 2 * dt * f[d] / m) / (2 + c * dt);
			s->se3.position[d] += dt * s->vel[d];
		}
		// Rotations: about z alone in 2D; in 3D each axis, the sphere turning by the rotation vector.
		for (int d = threeD ? 0 : 2; d < 3; ++d) {
			const Real Jd = (*J[d])[id];
			s->angVel[d]  = (s->blockedDOFs & LogTimeSolver::kRotDOF[d]) || !(Jd > 0)
			         ? 0
			         : ((2 - c * dt) * s->angVel[d] + 2 * dt * t[d] / Jd) / (2 + c * dt);
		}
		const Real turn = threeD ? dt * s->angVel.norm() : dt * s->angVel[2];
		// a free disc turns its orientation at every iteration (by 0 at rest), a sphere when it turns
		if (threeD ? turn > 0 : !(s->blockedDOFs & State::DOF_RZ) && inertiaZ[id] > 0) {
			const Vector3r axis = threeD ? Vector3r(s->angVel.normalized()) : Vector3r::UnitZ();
			s->se3.orientation  = Quaternionr(Eigen::AngleAxis<Real>(turn, axis)) * s->se3.orientation;
			s->se3.orientation.normalize();
		}
	}
}

} // namespace yade
