// SPDX-License-Identifier: GPL-2.0-or-later
// Laguerre (power) diagram of spheres clipped to a box, via CGAL's 3D regular triangulation.
#pragma once
#include <array>
#include <vector>

namespace swelldem { namespace meso {

// The six sides of the box [0,W]x[0,H]x[0,D], in the order of box_area below;
// the outward normals are -x, +x, -y, +y, -z, +z.
enum BoxSide { kXLow = 0, kXHigh, kYLow, kYHigh, kZLow, kZHigh };

struct Laguerre3DFacet {
  int i, j;                 // i < j
  double area;              // mean of the areas seen from both cells
  double normal[3];         // unit, from centre i towards centre j
  double centroid[3];       // of the polygon
  long poly_begin, poly_end;  // its vertices in Laguerre3DResult::poly, counter-clockwise about normal
};

struct Laguerre3DResult {
  std::vector<double> cell_volume;
  std::vector<std::array<double, 6>> box_area;  // per sphere, its cell's area on each BoxSide
  std::vector<Laguerre3DFacet> facets;          // sorted by (i, j)
  std::vector<double> poly;                     // x, y, z of the facet polygons' vertices
  double volume_sum = 0;
  double max_asymmetry = 0;   // max |area_i - area_j| over neighbour pairs
  long hidden = 0;            // spheres that are no vertex of the triangulation
  long empty_cells = 0;       // cells of zero volume (the hidden ones included)
  int dimension = 0;          // of the triangulation
  long neighbour_pairs = 0;   // pairs of neighbours in the triangulation
  long zero_area = 0;         // of those, with no facet of area above zero_threshold
  double zero_threshold = 0;  // facet area below which a facet is dropped
  long cap_sorts = 0;         // clips whose new face had to be ordered by angle (see laguerre3d.cpp)
};

// Throws std::invalid_argument on bad arguments (the message names the argument and its range).
Laguerre3DResult laguerre_box(const std::vector<double>& x, const std::vector<double>& y,
                              const std::vector<double>& z, const std::vector<double>& r, double width,
                              double height, double depth);

}}  // namespace swelldem::meso
