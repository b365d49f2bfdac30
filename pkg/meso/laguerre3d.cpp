// SPDX-License-Identifier: GPL-2.0-or-later
//
// Power cells of spheres clipped to the box [0,W]x[0,H]x[0,D].
//
// CGAL's 3D regular triangulation of the weighted points (centre, r^2) gives the
// neighbour graph of the power diagram: every facet of positive area is an edge of
// any regular triangulation of the points, so clipping by the triangulation
// neighbours alone cannot miss a facet (degenerate sets, such as lattices, only add
// edges whose facet has zero area). The cell of sphere i is the box clipped by the
// half-spaces {p : pow_i(p) <= pow_j(p)}, pow_k(p) = |p - c_k|^2 - r_k^2, in
// coordinates relative to c_i. Each face of the convex polyhedron carries what made
// it (a neighbour or a side of the box), which attributes every facet polygon.
#include "laguerre3d.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace swelldem { namespace meso {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb0 = CGAL::Regular_triangulation_vertex_base_3<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K, Vb0>;
using Cb = CGAL::Regular_triangulation_cell_base_3<K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using RT = CGAL::Regular_triangulation_3<K, Tds>;
using WPoint = K::Weighted_point_3;
using Point = K::Point_3;

struct V3 {
  double x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(V3 a) { return std::sqrt(dot(a, a)); }

// Face labels: >= 0 is whatever the caller clips with (here a slot of the neighbour
// lists), a side of the box is -1 - BoxSide.
inline int box_label(int side) { return -1 - side; }
inline int box_side(int label) { return -1 - label; }

// A vertex closer to a clipping plane than this, relative to the cell's radius, is
// taken as lying on it. Lattices put vertices exactly on later planes; without the
// band, rounding would cut slivers of ~1e-16 relative width and invent facets. The
// coordinates carry errors of a few ulp of the box size at most, far below the band,
// and the band itself can move the cell by no more than 1e-11 of its radius.
constexpr double kOnPlane = 1e-11;

// A convex polyhedron as faces (cyclic vertex lists, counter-clockwise about the
// outward normal) over a shared vertex pool. Sharing the vertices lets the new face
// of a clip be chained from the edges cut in the old faces, so its order comes from
// the topology, not from sorting angles that coincide in degenerate cells.
class ConvexCell {
 public:
  struct Face {
    int label;
    int begin, count;  // in idx()
  };

  void reset_box(V3 lo, V3 hi) {
    vert_.clear();
    for (int k = 0; k < 8; ++k)
      vert_.push_back({(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
    static const int quad[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    face_.clear();
    idx_.clear();
    for (int s = 0; s < 6; ++s) {
      face_.push_back({box_label(s), int(idx_.size()), 4});
      idx_.insert(idx_.end(), quad[s], quad[s] + 4);
    }
    radius_ = 0;
    for (const V3& v : vert_) radius_ = std::max(radius_, norm(v));
  }

  void clear() {
    face_.clear();
    idx_.clear();
  }

  bool empty() const { return face_.empty(); }
  const std::vector<Face>& faces() const { return face_; }
  const std::vector<int>& idx() const { return idx_; }
  const V3& vertex(int v) const { return vert_[v]; }
  long cap_sorts() const { return cap_sorts_; }

  // Keeps the part where dot(nrm, p) <= c; the new face, if any, gets `label`.
  void clip(V3 nrm, double c, int label) {
    if (face_.empty()) return;
    const std::size_t nv = vert_.size();
    f_.assign(nv, 0.0);
    cls_.assign(nv, 2);  // 2: not referenced by any face
    const double tol = kOnPlane * norm(nrm) * radius_;
    int outs = 0, ins = 0;
    for (int v : idx_) {
      if (cls_[v] != 2) continue;
      const double f = dot(nrm, vert_[v]) - c;
      f_[v] = f;
      cls_[v] = f > tol ? 1 : (f < -tol ? -1 : 0);
      outs += cls_[v] == 1;
      ins += cls_[v] == -1;
    }
    if (outs == 0) return;  // the plane misses the cell or only touches it
    if (ins == 0) {         // nothing of positive volume is left
      clear();
      return;
    }
    nface_.clear();
    nidx_.clear();
    cuts_.clear();
    cap_.clear();
    for (const Face& F : face_) {
      const int* v = &idx_[F.begin];
      const int m = F.count;
      int s = -1;
      bool any_out = false;
      for (int k = 0; k < m; ++k) {
        if (s < 0 && cls_[v[k]] <= 0) s = k;
        any_out |= cls_[v[k]] == 1;
      }
      if (s < 0) continue;  // wholly outside
      Face G{F.label, int(nidx_.size()), 0};
      if (!any_out) {
        nidx_.insert(nidx_.end(), v, v + m);
      } else {
        // Walk from a kept vertex; every run of outside vertices is replaced by the
        // edge exit -> entry on the plane, which the new face walks entry -> exit.
        int exit_v = -1;
        for (int t = 0; t < m; ++t) {
          const int a = v[(s + t) % m], b = v[(s + t + 1) % m];
          const int ca = cls_[a], cb = cls_[b];
          if (ca <= 0) nidx_.push_back(a);
          if (ca <= 0 && cb == 1) {
            exit_v = ca == 0 ? a : cut(a, b);
            if (ca != 0) nidx_.push_back(exit_v);
          } else if (ca == 1 && cb <= 0) {
            const int entry = cb == 0 ? b : cut(a, b);
            if (cb != 0) nidx_.push_back(entry);
            if (entry != exit_v) cap_.push_back({entry, exit_v});
          }
        }
      }
      G.count = int(nidx_.size()) - G.begin;
      if (G.count >= 3)
        nface_.push_back(G);
      else
        nidx_.resize(G.begin);
    }
    if (cap_.size() >= 3) {
      Face C{label, int(nidx_.size()), 0};
      if (!chain_cap()) order_cap_by_angle(nrm);
      C.count = int(nidx_.size()) - C.begin;
      if (C.count >= 3)
        nface_.push_back(C);
      else
        nidx_.resize(C.begin);
    }
    face_.swap(nface_);
    idx_.swap(nidx_);
    radius_ = 0;
    for (int v : idx_) radius_ = std::max(radius_, norm(vert_[v]));
  }

 private:
  // The point where the plane cuts edge a-b, made once per edge so both faces share it.
  int cut(int a, int b) {
    const int lo = std::min(a, b), hi = std::max(a, b);
    for (const auto& e : cuts_)
      if (e.first.first == lo && e.first.second == hi) return e.second;
    const double t = f_[lo] / (f_[lo] - f_[hi]);
    const V3 p = vert_[lo], q = vert_[hi];
    vert_.push_back(p + t * (q - p));
    f_.push_back(0.0);
    cls_.push_back(0);
    const int id = int(vert_.size()) - 1;
    cuts_.push_back({{lo, hi}, id});
    return id;
  }

  bool chain_cap() {
    const std::size_t m = cap_.size();
    const int start = cap_[0].first;
    int cur = start;
    const std::size_t begin = nidx_.size();
    for (std::size_t step = 0; step < m; ++step) {
      nidx_.push_back(cur);
      int next = -1, found = 0;
      for (const auto& e : cap_)
        if (e.first == cur) {
          next = e.second;
          ++found;
        }
      if (found != 1) break;
      cur = next;
      if (cur == start) return step + 1 == m;
    }
    nidx_.resize(begin);
    return false;
  }

  // Only when the cut edges do not form one cycle, which the on-plane band could
  // cause in a nearly degenerate cell; counted in the result.
  void order_cap_by_angle(V3 nrm) {
    ++cap_sorts_;
    std::vector<int> ids;
    for (const auto& e : cap_) {
      ids.push_back(e.first);
      ids.push_back(e.second);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    V3 g{0, 0, 0};
    for (int v : ids) g = g + vert_[v];
    g = (1.0 / double(ids.size())) * g;
    const V3 n = (1.0 / norm(nrm)) * nrm;
    const V3 helper = std::fabs(n.x) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0};
    V3 u = cross(helper, n);
    u = (1.0 / norm(u)) * u;
    const V3 w = cross(n, u);
    std::vector<std::pair<double, int>> ang;
    for (int v : ids) {
      const V3 d = vert_[v] - g;
      ang.push_back({std::atan2(dot(d, w), dot(d, u)), v});
    }
    std::sort(ang.begin(), ang.end());
    for (const auto& a : ang) nidx_.push_back(a.second);
  }

  std::vector<V3> vert_;
  std::vector<Face> face_, nface_;
  std::vector<int> idx_, nidx_;
  std::vector<double> f_;
  std::vector<int> cls_;
  std::vector<std::pair<std::pair<int, int>, int>> cuts_;
  std::vector<std::pair<int, int>> cap_;  // entry -> exit
  double radius_ = 0;
  long cap_sorts_ = 0;
};

struct FaceGeometry {
  V3 area_vec{0, 0, 0};
  V3 centroid{0, 0, 0};
  double vol6 = 0;  // six times the volume of the cone from the origin (the centre) to the face
};

FaceGeometry face_geometry(const ConvexCell& cell, const ConvexCell::Face& F) {
  FaceGeometry g;
  const int* v = &cell.idx()[F.begin];
  const V3 p0 = cell.vertex(v[0]);
  double wsum = 0;
  for (int k = 1; k + 1 < F.count; ++k) {
    const V3 p1 = cell.vertex(v[k]), p2 = cell.vertex(v[k + 1]);
    const V3 cr = cross(p1 - p0, p2 - p0);
    g.area_vec = g.area_vec + 0.5 * cr;
    const double w = norm(cr);
    g.centroid = g.centroid + (w / 3.0) * (p0 + p1 + p2);
    wsum += w;
    g.vol6 += dot(p0, cross(p1, p2));
  }
  if (wsum > 0)
    g.centroid = (1.0 / wsum) * g.centroid;
  else
    g.centroid = p0;
  return g;
}

// Shortest text that reads back as v, so a message shows the value as the caller wrote it.
std::string num(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

void validate(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
              const std::vector<double>& r, double W, double H, double D) {
  const std::size_t n = x.size();
  if (y.size() != n || z.size() != n || r.size() != n)
    throw std::invalid_argument("x, y, z, r must have the same length (got " + std::to_string(x.size()) + ", " +
                                std::to_string(y.size()) + ", " + std::to_string(z.size()) + ", " +
                                std::to_string(r.size()) + ")");
  const char* names[3] = {"width W", "height H", "depth D"};
  const double dims[3] = {W, H, D};
  for (int a = 0; a < 3; ++a)
    if (!(std::isfinite(dims[a]) && dims[a] > 0))
      throw std::invalid_argument(std::string(names[a]) + " = " + num(dims[a]) + " must be finite and > 0");
  const std::vector<double>* coord[3] = {&x, &y, &z};
  const char* cname[3] = {"x", "y", "z"};
  const char* dname[3] = {"W", "H", "D"};
  for (std::size_t k = 0; k < n; ++k) {
    for (int a = 0; a < 3; ++a) {
      const double c = (*coord[a])[k];
      if (!std::isfinite(c))
        throw std::invalid_argument(std::string(cname[a]) + "[" + std::to_string(k) + "] = " + num(c) +
                                    " must be finite");
      if (c < 0 || c > dims[a])
        throw std::invalid_argument(std::string(cname[a]) + "[" + std::to_string(k) + "] = " + num(c) +
                                    " is outside the box: must be in [0, " + dname[a] + "] = [0, " +
                                    num(dims[a]) + "]");
    }
    if (!(std::isfinite(r[k]) && r[k] > 0))
      throw std::invalid_argument("r[" + std::to_string(k) + "] = " + num(r[k]) + " must be finite and > 0");
  }
}

}  // namespace

Laguerre3DResult laguerre_box(const std::vector<double>& x, const std::vector<double>& y,
                              const std::vector<double>& z, const std::vector<double>& r, double W, double H,
                              double D) {
  validate(x, y, z, r, W, H, D);
  const std::size_t n = x.size();
  Laguerre3DResult res;
  res.cell_volume.assign(n, 0.0);
  res.box_area.assign(n, std::array<double, 6>{0, 0, 0, 0, 0, 0});
  if (n == 0) return res;

  // Neighbour lists (CSR, sorted) from the triangulation's edges, which exist in
  // every dimension from 1 on (coplanar or collinear centres included).
  std::vector<char> present(n, 0);
  std::vector<std::pair<int, int>> edges;
  {
    RT rt;
    std::vector<std::pair<WPoint, int>> pts;
    pts.reserve(n);
    for (std::size_t k = 0; k < n; ++k) pts.emplace_back(WPoint(Point(x[k], y[k], z[k]), r[k] * r[k]), int(k));
    rt.insert(pts.begin(), pts.end());
    res.dimension = rt.dimension();
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) present[v->info()] = 1;
    if (rt.dimension() >= 1) {
      edges.reserve(2 * rt.number_of_finite_edges());
      for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
        const int i = e->first->vertex(e->second)->info();
        const int j = e->first->vertex(e->third)->info();
        edges.emplace_back(i, j);
        edges.emplace_back(j, i);
      }
    }
  }  // the triangulation's memory goes before the cells are built
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<long> off(n + 1, 0);
  std::vector<int> adj(edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) {
    ++off[edges[k].first + 1];
    adj[k] = edges[k].second;
  }
  std::vector<std::pair<int, int>>().swap(edges);
  for (std::size_t i = 0; i < n; ++i) off[i + 1] += off[i];
  res.neighbour_pairs = long(adj.size()) / 2;
  for (std::size_t k = 0; k < n; ++k) res.hidden += !present[k];

  auto slot_of = [&](int i, int j) {  // position of j in i's list
    const auto b = adj.begin() + off[i], e = adj.begin() + off[i + 1];
    return long(std::lower_bound(b, e, j) - adj.begin());
  };

  std::vector<double> slot_area(adj.size(), 0.0);
  std::vector<long> slot_facet(adj.size(), -1);  // for slots of j > i: the facet made for the pair
  std::vector<Laguerre3DFacet> facets;
  std::vector<double> poly;
  facets.reserve(adj.size() / 2);

  ConvexCell cell;
  std::vector<std::pair<double, long>> order;
  for (std::size_t i = 0; i < n; ++i) {
    if (!present[i]) continue;  // hidden: empty cell
    const V3 ci{x[i], y[i], z[i]};
    const double wi = r[i] * r[i];
    cell.reset_box({-ci.x, -ci.y, -ci.z}, {W - ci.x, H - ci.y, D - ci.z});
    // Nearest planes first: they remove the far box corners at once, so later cuts
    // work on a small cell (fewer vertices, and coordinates of the cell's own size).
    order.clear();
    for (long s = off[i]; s < off[i + 1]; ++s) {
      const int j = adj[s];
      const V3 d{x[j] - ci.x, y[j] - ci.y, z[j] - ci.z};
      const double dd = dot(d, d);
      if (dd == 0) continue;
      order.push_back({(dd + wi - r[j] * r[j]) / (2 * std::sqrt(dd)), s});
    }
    std::sort(order.begin(), order.end());
    for (const auto& o : order) {
      if (cell.empty()) break;
      const int j = adj[o.second];
      // pow_i(p) <= pow_j(p)  <=>  2 p.d <= |d|^2 + w_i - w_j, with p, d relative to c_i
      const V3 d{x[j] - ci.x, y[j] - ci.y, z[j] - ci.z};
      cell.clip(2.0 * d, dot(d, d) + wi - r[j] * r[j], int(o.second));
    }
    double vol6 = 0;
    for (const auto& F : cell.faces()) {
      const FaceGeometry g = face_geometry(cell, F);
      vol6 += g.vol6;
      if (F.label < 0) {
        const int side = box_side(F.label);
        const double sign = (side % 2 == 0) ? -1.0 : 1.0;
        const double comp[3] = {g.area_vec.x, g.area_vec.y, g.area_vec.z};
        res.box_area[i][side] += sign * comp[side / 2];
        continue;
      }
      const long s = F.label;
      const int j = adj[s];
      const V3 d{x[j] - ci.x, y[j] - ci.y, z[j] - ci.z};
      const V3 nhat = (1.0 / norm(d)) * d;
      const double area = dot(g.area_vec, nhat);
      slot_area[s] += area;
      // The pair's polygon comes from the lower index's cell, or from the other cell
      // when the lower one saw no face.
      long* made = nullptr;
      bool flip = false;
      if (int(i) < j) {
        made = &slot_facet[s];
      } else {
        made = &slot_facet[slot_of(j, int(i))];
        flip = true;
      }
      if (*made >= 0) continue;
      Laguerre3DFacet fct{};
      fct.i = std::min(int(i), j);
      fct.j = std::max(int(i), j);
      fct.area = 0;
      const V3 nrm = flip ? -1.0 * nhat : nhat;
      fct.normal[0] = nrm.x;
      fct.normal[1] = nrm.y;
      fct.normal[2] = nrm.z;
      const V3 cg = g.centroid + ci;
      fct.centroid[0] = cg.x;
      fct.centroid[1] = cg.y;
      fct.centroid[2] = cg.z;
      fct.poly_begin = long(poly.size()) / 3;
      for (int k = 0; k < F.count; ++k) {
        const int kk = flip ? F.count - 1 - k : k;
        const V3 p = cell.vertex(cell.idx()[F.begin + kk]) + ci;
        poly.push_back(p.x);
        poly.push_back(p.y);
        poly.push_back(p.z);
      }
      fct.poly_end = long(poly.size()) / 3;
      *made = long(facets.size());
      facets.push_back(fct);
    }
    res.cell_volume[i] = vol6 / 6.0;
  }
  res.cap_sorts = cell.cap_sorts();
  for (std::size_t i = 0; i < n; ++i) {
    res.volume_sum += res.cell_volume[i];
    res.empty_cells += !(res.cell_volume[i] > 0);
  }

  const double scale = std::cbrt(W * H * D / double(n));
  res.zero_threshold = 1e-12 * scale * scale;
  for (std::size_t i = 0; i < n; ++i)
    for (long s = off[i]; s < off[i + 1]; ++s) {
      const int j = adj[s];
      if (j <= int(i)) continue;
      const double ai = slot_area[s], aj = slot_area[slot_of(j, int(i))];
      res.max_asymmetry = std::max(res.max_asymmetry, std::fabs(ai - aj));
      if (slot_facet[s] >= 0) facets[slot_facet[s]].area = 0.5 * (ai + aj);
    }

  // Sorted by pair, polygons copied in that order, the zero ones left out.
  std::vector<long> keep;
  keep.reserve(facets.size());
  for (long k = 0; k < long(facets.size()); ++k)
    if (facets[k].area > res.zero_threshold) keep.push_back(k);
  std::sort(keep.begin(), keep.end(), [&](long a, long b) {
    return facets[a].i != facets[b].i ? facets[a].i < facets[b].i : facets[a].j < facets[b].j;
  });
  res.facets.reserve(keep.size());
  long nverts = 0;
  for (long k : keep) nverts += facets[k].poly_end - facets[k].poly_begin;
  res.poly.reserve(3 * nverts);
  for (long k : keep) {
    Laguerre3DFacet f = facets[k];
    const long b = long(res.poly.size()) / 3;
    res.poly.insert(res.poly.end(), poly.begin() + 3 * f.poly_begin, poly.begin() + 3 * f.poly_end);
    f.poly_begin = b;
    f.poly_end = long(res.poly.size()) / 3;
    res.facets.push_back(f);
  }
  res.zero_area = res.neighbour_pairs - long(res.facets.size());
  return res;
}

}}  // namespace swelldem::meso
