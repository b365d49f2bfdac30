// SPDX-License-Identifier: GPL-2.0-or-later
// Laguerre (power) diagram of discs clipped to a rectangle, via CGAL's regular triangulation.
#pragma once
#include <vector>

namespace swelldem { namespace meso {

struct LaguerreFacet {
  int i, j;            // i < j
  double length;       // mean of the lengths seen from both cells
  double x1, y1, x2, y2;
};

struct LaguerreResult {
  std::vector<double> cell_area;
  std::vector<LaguerreFacet> facets;
  double area_sum = 0;
  double max_asymmetry = 0;   // max |len_i - len_j| over facets
  long hidden = 0;            // discs without a cell
  int dimension = 0;          // of the triangulation
  long neighbour_pairs = 0;   // pairs of neighbours in the triangulation
  long zero_length = 0;       // of those, with no clipped edge of positive length
  double zero_threshold = 0;  // edge length below which an edge is ignored
};

// Throws std::invalid_argument on bad arguments.
LaguerreResult laguerre_rectangle(const std::vector<double>& x, const std::vector<double>& y,
                                  const std::vector<double>& r, double width, double height);

}}  // namespace swelldem::meso
