// SPDX-License-Identifier: GPL-2.0-or-later
//
// Power cells of discs clipped to the rectangle [0,W]x[0,H].
//
// CGAL's 2D regular triangulation of the weighted points (centre, r^2) gives the
// neighbour graph of the power diagram. The cell of disc i is then the box
// clipped by the half-planes {p : pow_i(p) <= pow_j(p)} of its neighbours j,
// pow_k(p) = |p - c_k|^2 - r_k^2, by convex-polygon clipping in coordinates
// relative to c_i. Every edge of a clipped cell carries the index of what made
// it (a neighbour or a side of the box), which gives the shared facets.
#include "laguerre.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace swelldem { namespace meso {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb0 = CGAL::Regular_triangulation_vertex_base_2<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K, Vb0>;
using Fb = CGAL::Regular_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using RT = CGAL::Regular_triangulation_2<K, Tds>;
using WPoint = K::Weighted_point_2;
using Point = K::Point_2;

constexpr int kBoxBottom = -1, kBoxRight = -2, kBoxTop = -3, kBoxLeft = -4;

struct PolyVertex {
  double x, y;  // relative to the disc centre
  int label;    // what made the edge that starts at this vertex
};

// Keeps the part of the convex polygon where a x + b y <= c; the new edge gets `label`.
void clip(std::vector<PolyVertex>& poly, std::vector<PolyVertex>& scratch, double a, double b,
          double c, int label) {
  scratch.clear();
  const std::size_t n = poly.size();
  if (n == 0) return;
  for (std::size_t k = 0; k < n; ++k) {
    const PolyVertex& p = poly[k];
    const PolyVertex& q = poly[(k + 1) % n];
    double fp = a * p.x + b * p.y - c, fq = a * q.x + b * q.y - c;
    bool pin = fp <= 0, qin = fq <= 0;
    if (pin) scratch.push_back(p);
    if (pin != qin) {
      double t = fp / (fp - fq);
      PolyVertex s{p.x + t * (q.x - p.x), p.y + t * (q.y - p.y), pin ? label : p.label};
      scratch.push_back(s);
    }
  }
  poly.swap(scratch);
}

double polygon_area(const std::vector<PolyVertex>& poly) {
  double s = 0;
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < n; ++k) {
    const PolyVertex& p = poly[k];
    const PolyVertex& q = poly[(k + 1) % n];
    s += p.x * q.y - q.x * p.y;
  }
  return 0.5 * s;
}

struct SideEdge {
  double length = -1;  // -1: not seen from this side
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
};

}  // namespace

LaguerreResult laguerre_rectangle(const std::vector<double>& x, const std::vector<double>& y,
                                  const std::vector<double>& r, double W, double H) {
  const std::size_t n = x.size();
  if (y.size() != n || r.size() != n) throw std::invalid_argument("x, y, r must have the same length");
  if (!(std::isfinite(W) && W > 0 && std::isfinite(H) && H > 0))
    throw std::invalid_argument("width and height must be finite and > 0");
  for (std::size_t k = 0; k < n; ++k) {
    if (!(std::isfinite(x[k]) && std::isfinite(y[k]) && std::isfinite(r[k]) && r[k] >= 0))
      throw std::invalid_argument("disc " + std::to_string(k) + " has a non-finite centre or a negative radius");
    if (x[k] < 0 || x[k] > W || y[k] < 0 || y[k] > H)
      throw std::invalid_argument("centre of disc " + std::to_string(k) + " is outside the box");
  }
  LaguerreResult res;
  res.cell_area.assign(n, 0.0);
  if (n == 0) return res;

  // Neighbour lists from the regular triangulation.
  std::vector<std::vector<int>> nbr(n);
  RT rt;
  {
    std::vector<std::pair<WPoint, int>> pts;
    pts.reserve(n);
    for (std::size_t k = 0; k < n; ++k) pts.emplace_back(WPoint(Point(x[k], y[k]), r[k] * r[k]), int(k));
    rt.insert(pts.begin(), pts.end());
  }
  res.dimension = rt.dimension();
  std::vector<char> present(n, 0);
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) present[v->info()] = 1;
  if (rt.dimension() == 2) {
    for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
      auto f = e->first;
      int i = f->vertex(RT::cw(e->second))->info();
      int j = f->vertex(RT::ccw(e->second))->info();
      nbr[i].push_back(j);
      nbr[j].push_back(i);
    }
  } else {
    // Degenerate (fewer than 3 discs, or all centres aligned): every pair.
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        if (i != j) nbr[i].push_back(int(j));
  }
  for (auto& l : nbr) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }

  const double scale = std::sqrt(W * H / double(n));
  res.zero_threshold = 1e-12 * scale;
  std::unordered_map<unsigned long long, std::pair<SideEdge, SideEdge>> edges;
  edges.reserve(3 * n);
  auto key = [](int i, int j) { return (static_cast<unsigned long long>(unsigned(i)) << 32) | unsigned(j); };

  std::vector<PolyVertex> poly, scratch;
  for (std::size_t i = 0; i < n; ++i) {
    const double cx = x[i], cy = y[i], wi = r[i] * r[i];
    poly.clear();
    poly.push_back({-cx, -cy, kBoxBottom});
    poly.push_back({W - cx, -cy, kBoxRight});
    poly.push_back({W - cx, H - cy, kBoxTop});
    poly.push_back({-cx, H - cy, kBoxLeft});
    if (res.dimension == 2 && !present[i]) poly.clear();  // hidden: empty cell
    for (int j : nbr[i]) {
      if (poly.empty()) break;
      // pow_i(p) <= pow_j(p)  <=>  2 p.d <= |d|^2 + w_i - w_j, with p, d relative to c_i
      double dx = x[j] - cx, dy = y[j] - cy;
      double c = dx * dx + dy * dy + wi - r[j] * r[j];
      clip(poly, scratch, 2 * dx, 2 * dy, c, j);
      if (poly.empty()) break;
    }
    double a = polygon_area(poly);
    res.cell_area[i] = a;
    const std::size_t m = poly.size();
    for (std::size_t k = 0; k < m; ++k) {
      const PolyVertex& p = poly[k];
      if (p.label < 0) continue;
      const PolyVertex& q = poly[(k + 1) % m];
      double len = std::hypot(q.x - p.x, q.y - p.y);
      int j = p.label;
      int lo = std::min(int(i), j), hi = std::max(int(i), j);
      auto& slot = edges[key(lo, hi)];
      SideEdge& se = (int(i) == lo) ? slot.first : slot.second;
      if (se.length < 0) se.length = 0;
      se.length += len;  // a cell is convex: one edge per neighbour, but be safe
      se.x1 = p.x + cx; se.y1 = p.y + cy; se.x2 = q.x + cx; se.y2 = q.y + cy;
    }
  }
  for (double a : res.cell_area) res.area_sum += a;
  for (std::size_t i = 0; i < n; ++i)
    if (!(res.cell_area[i] > 0)) ++res.hidden;

  // Triangulation neighbour pairs (for the report) and facets.
  long pairs = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int j : nbr[i])
      if (int(i) < j) ++pairs;
  res.neighbour_pairs = pairs;
  res.facets.reserve(edges.size());
  for (const auto& kv : edges) {
    const SideEdge& a = kv.second.first;
    const SideEdge& b = kv.second.second;
    double la = std::max(0.0, a.length), lb = std::max(0.0, b.length);
    res.max_asymmetry = std::max(res.max_asymmetry, std::fabs(la - lb));
    double len = 0.5 * (la + lb);
    if (len <= res.zero_threshold) continue;
    const SideEdge& s = a.length >= 0 ? a : b;
    LaguerreFacet f;
    f.i = int(kv.first >> 32);
    f.j = int(kv.first & 0xffffffffULL);
    f.length = len;
    f.x1 = s.x1; f.y1 = s.y1; f.x2 = s.x2; f.y2 = s.y2;
    res.facets.push_back(f);
  }
  std::sort(res.facets.begin(), res.facets.end(), [](const LaguerreFacet& p, const LaguerreFacet& q) {
    return p.i != q.i ? p.i < q.i : p.j < q.j;
  });
  res.zero_length = pairs - long(res.facets.size());
  return res;
}

}}  // namespace swelldem::meso
