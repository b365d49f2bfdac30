// SPDX-License-Identifier: GPL-2.0-or-later
// Compact random sphere packing of a box (collective rearrangement), YADE-free.
#pragma once
#include <cstdint>
#include <vector>

namespace swelldem { namespace meso {

struct Packing3DStats {
  double density = 0;          // sphere volume / box volume
  double target_density = 0;   // volume of the radii drawn / box volume, before any removal
  long sweeps = 0;             // overlap-removal sweeps over all spheres
  long pushes = 0;             // pair separations made in those sweeps
  long removed = 0;            // spheres dropped to unjam the relaxation
  double near_contacts = 0;    // pairs with a gap below 0.025 rmax, per sphere (x2 = coordination)
  double max_overlap_rel = 0;  // max overlap / rmax found by the final check (<= 0: none)
};

struct Packing3D {
  std::vector<double> x, y, z, r;
  Packing3DStats stats;
};

// Spheres of radii uniform in [rmin, rmax] in the box [0,W]x[0,H]x[0,D], none overlapping,
// none crossing a side; numbered in Morton (Z-curve) order of their centres on a grid of
// cubic cells of side rmin (at most one centre a cell, so the order is strict).
// Throws std::invalid_argument on bad arguments (the message names the argument and its range).
Packing3D pack_box(double width, double height, double depth, double rmin, double rmax, std::uint64_t seed);

}}  // namespace swelldem::meso
