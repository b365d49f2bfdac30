// SPDX-License-Identifier: GPL-2.0-or-later
// Adaptive dynamic relaxation (Underwood) on a swelldem scene, 2D (discs: x, y, rotation z) or 3D
// (spheres: three translations and three rotations): fictitious masses from a
// Gershgorin bound of the contact stiffness, damping from a Rayleigh quotient of a local stiffness
// estimate, a damped leapfrog step per iteration. AdrLogTimeIntegrator reaches every equilibrium
// with it; ImplicitLogTimeSolver uses it where Newton's active set does not settle.
#pragma once
#include "LogTimeSolver.hpp"

namespace yade {

class DynamicRelaxation {
public:
	// Central differences are stable while dt^2 lambda_max(M^-1 K) < 4. The Gershgorin masses make
	// that product at most 4, and exactly 4 for two free discs in contact (or any isolated pair):
	// their contact mode then flips sign every iteration and no damping removes it (its root stays
	// at -1). A 2 % margin makes it decay (two free discs settle in a few hundred iterations a step)
	// and changes paper runs by less than the ADR tolerance does (docs/contact-law-and-solver.md).
	static constexpr Real kDefaultMassSafety = 1.02;
	static constexpr Real kDefaultMaxDamping = 1.8;

	std::vector<Real> massX, massY, inertiaZ; // fictitious masses and rotational inertia per body
	std::vector<Real> massZ, inertiaX, inertiaY; // the same, 3D only (empty in 2D)
	std::vector<Real> prevForce;              // residual of the previous iteration, 3 per body (x, y, torque z), 6 in 3D
	std::vector<Real> initialPos;             // positions when it started, 2 per body (3 in 3D), for the damping estimate
	long              nContactsSeen = -1;     // real contacts when the masses were computed
	int               nDim          = 2;      // the scene's dimension (LogTimeSolver.nDim)

	/// Starts from rest at the current positions, for a scene of dimension dim (2 or 3).
	void start(const Scene* scene, int dim);
	/// A new physical step starts from rest.
	void rest() { std::fill(prevForce.begin(), prevForce.end(), 0.0); }
	void computeMasses(const Scene* scene, Real massSafety);
	/// Adds a stiffness k [N/m] acting on one body's axis (a spring) to its mass, as computeMasses does for contacts.
	void addStiffness(const Scene* scene, Real massSafety, int id, int axis, Real k)
	{
		(axis == 0 ? massX : axis == 1 ? massY : massZ)[id] += 0.25 * scene->dt * scene->dt * massSafety * k;
	}
	/// Damping c [1/dt] from the Rayleigh quotient, at most maxDamping / dt.
	Real damping(Scene* scene, Real maxDamping) const; // (YADE's force getter is not const)
	void leapfrog(Scene* scene, Real c);
	template <class Archive> void serialize(Archive& ar, unsigned)
	{
		ar& boost::serialization::make_nvp("massX", massX);
		ar& boost::serialization::make_nvp("massY", massY);
		ar& boost::serialization::make_nvp("inertiaZ", inertiaZ);
		ar& boost::serialization::make_nvp("prevForce", prevForce);
		ar& boost::serialization::make_nvp("initialPos", initialPos);
		ar& boost::serialization::make_nvp("nContactsSeen", nContactsSeen);
		ar& boost::serialization::make_nvp("nDim", nDim);
		ar& boost::serialization::make_nvp("massZ", massZ);
		ar& boost::serialization::make_nvp("inertiaX", inertiaX);
		ar& boost::serialization::make_nvp("inertiaY", inertiaY);
	}
};

} // namespace yade
BOOST_CLASS_IMPLEMENTATION(yade::DynamicRelaxation, boost::serialization::object_serializable)
BOOST_CLASS_TRACKING(yade::DynamicRelaxation, boost::serialization::track_never)
