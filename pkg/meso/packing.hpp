// SPDX-License-Identifier: GPL-2.0-or-later
// Compact random disc packing of a rectangle (advancing front), YADE-free.
#pragma once
#include <cstdint>
#include <vector>

namespace swelldem { namespace meso {

struct PackingStats {
  double density = 0;          // disc area / box area
  long abandoned = 0;          // front pairs where no disc could be placed
  long top_fill = 0;           // discs added by the final pass along the top side
  long collapses = 0;          // front collapses (overlap with a front object)
  long enlarged = 0;           // discs enlarged (within [rmin, rmax]) to bridge a gap
  double max_overlap_rel = 0;  // max overlap / rmax found by the final brute check
};

struct Packing {
  std::vector<double> x, y, r;
  PackingStats stats;
};

// Throws std::invalid_argument on bad arguments.
Packing pack_rectangle(double width, double height, double rmin, double rmax, std::uint64_t seed);

}}  // namespace swelldem::meso
