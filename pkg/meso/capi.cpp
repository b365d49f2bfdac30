// SPDX-License-Identifier: GPL-2.0-or-later
// extern "C" entry points of swelldem_geom (see swelldem_geom.h).
#include "swelldem_geom.h"

#include <algorithm>
#include <exception>
#include <string>

#include "core/PairKind.hpp"
#include "laguerre.hpp"
#include "laguerre3d.hpp"
#include "packing.hpp"
#include "packing3d.hpp"

namespace {
thread_local std::string g_last_error;

long fail(const std::string& msg) {
  g_last_error = msg;
  return -1;
}
}  // namespace

extern "C" {

const char* swd_geom_version(void) { return "0.1.0"; }

const char* swd_geom_last_error(void) { return g_last_error.c_str(); }

long swd_pack_rectangle(double width, double height, double rmin, double rmax, unsigned long long seed,
                        long capacity, double* x, double* y, double* r, double* stats) {
  g_last_error.clear();
  try {
    if (!x || !y || !r) return fail("swd_pack_rectangle: null output buffer");
    auto p = swelldem::meso::pack_rectangle(width, height, rmin, rmax, seed);
    const long n = long(p.r.size());
    if (n > capacity)
      return fail("swd_pack_rectangle: capacity " + std::to_string(capacity) + " < " + std::to_string(n) + " discs");
    for (long k = 0; k < n; ++k) {
      x[k] = p.x[k];
      y[k] = p.y[k];
      r[k] = p.r[k];
    }
    if (stats) {
      stats[0] = p.stats.density;
      stats[1] = double(n);
      stats[2] = double(p.stats.abandoned);
      stats[3] = double(p.stats.top_fill);
      stats[4] = double(p.stats.collapses);
      stats[5] = p.stats.max_overlap_rel;
      stats[6] = double(p.stats.enlarged);
      stats[7] = 0;
    }
    return n;
  } catch (const std::exception& e) {
    return fail(std::string("swd_pack_rectangle: ") + e.what());
  } catch (...) {
    return fail("swd_pack_rectangle: unknown error");
  }
}

long swd_pack_box(double width, double height, double depth, double rmin, double rmax, unsigned long long seed,
                  long capacity, double* x, double* y, double* z, double* r, double* stats) {
  g_last_error.clear();
  try {
    if (!x || !y || !z || !r) return fail("swd_pack_box: null output buffer");
    auto p = swelldem::meso::pack_box(width, height, depth, rmin, rmax, seed);
    const long n = long(p.r.size());
    if (n > capacity)
      return fail("swd_pack_box: capacity " + std::to_string(capacity) + " < " + std::to_string(n) + " spheres");
    std::copy(p.x.begin(), p.x.end(), x);
    std::copy(p.y.begin(), p.y.end(), y);
    std::copy(p.z.begin(), p.z.end(), z);
    std::copy(p.r.begin(), p.r.end(), r);
    if (stats) {
      stats[0] = p.stats.density;
      stats[1] = double(n);
      stats[2] = p.stats.target_density;
      stats[3] = double(p.stats.sweeps);
      stats[4] = double(p.stats.pushes);
      stats[5] = p.stats.max_overlap_rel;
      stats[6] = double(p.stats.removed);
      stats[7] = p.stats.near_contacts;
    }
    return n;
  } catch (const std::exception& e) {
    return fail(std::string("swd_pack_box: ") + e.what());
  } catch (...) {
    return fail("swd_pack_box: unknown error");
  }
}

long swd_laguerre_rectangle(long n, const double* x, const double* y, const double* r, double width,
                            double height, long capacity, int* fi, int* fj, double* flen, double* fseg,
                            double* cell_area, double* stats) {
  g_last_error.clear();
  try {
    if (n < 0) return fail("swd_laguerre_rectangle: n < 0");
    if (n > 0 && (!x || !y || !r)) return fail("swd_laguerre_rectangle: null input buffer");
    if (!fi || !fj || !flen || !fseg || (n > 0 && !cell_area))
      return fail("swd_laguerre_rectangle: null output buffer");
    std::vector<double> vx(x, x + n), vy(y, y + n), vr(r, r + n);
    auto res = swelldem::meso::laguerre_rectangle(vx, vy, vr, width, height);
    const long m = long(res.facets.size());
    if (m > capacity)
      return fail("swd_laguerre_rectangle: capacity " + std::to_string(capacity) + " < " + std::to_string(m) +
                  " facets");
    for (long k = 0; k < n; ++k) cell_area[k] = res.cell_area[k];
    for (long k = 0; k < m; ++k) {
      const auto& f = res.facets[k];
      fi[k] = f.i;
      fj[k] = f.j;
      flen[k] = f.length;
      fseg[4 * k] = f.x1;
      fseg[4 * k + 1] = f.y1;
      fseg[4 * k + 2] = f.x2;
      fseg[4 * k + 3] = f.y2;
    }
    if (stats) {
      stats[0] = res.area_sum;
      stats[1] = res.max_asymmetry;
      stats[2] = double(res.hidden);
      stats[3] = double(res.dimension);
      stats[4] = double(res.neighbour_pairs);
      stats[5] = double(res.zero_length);
      stats[6] = res.zero_threshold;
      stats[7] = 0;
    }
    return m;
  } catch (const std::exception& e) {
    return fail(std::string("swd_laguerre_rectangle: ") + e.what());
  } catch (...) {
    return fail("swd_laguerre_rectangle: unknown error");
  }
}

long swd_laguerre_box(long n, const double* x, const double* y, const double* z, const double* r, double width,
                      double height, double depth, long capacity, long vcapacity, int* fi, int* fj, double* farea,
                      double* fnormal, double* fcentroid, long* fvoff, double* fverts, double* cell_volume,
                      double* box_area, long* needed, double* stats) {
  g_last_error.clear();
  try {
    if (n < 0) return fail("swd_laguerre_box: n = " + std::to_string(n) + " must be >= 0");
    if (n > 0 && (!x || !y || !z || !r)) return fail("swd_laguerre_box: null input buffer");
    if (!fi || !fj || !farea || !fnormal || !fcentroid || (n > 0 && (!cell_volume || !box_area)))
      return fail("swd_laguerre_box: null output buffer");
    if (fverts && !fvoff) return fail("swd_laguerre_box: fverts given without fvoff");
    std::vector<double> vx(x, x + n), vy(y, y + n), vz(z, z + n), vr(r, r + n);
    auto res = swelldem::meso::laguerre_box(vx, vy, vz, vr, width, height, depth);
    const long m = long(res.facets.size());
    const long nv = long(res.poly.size()) / 3;
    if (needed) {
      needed[0] = m;
      needed[1] = nv;
    }
    if (m > capacity)
      return fail("swd_laguerre_box: capacity " + std::to_string(capacity) + " < " + std::to_string(m) + " facets");
    if (fverts && nv > vcapacity)
      return fail("swd_laguerre_box: vcapacity " + std::to_string(vcapacity) + " < " + std::to_string(nv) +
                  " polygon vertices");
    for (long k = 0; k < n; ++k) {
      cell_volume[k] = res.cell_volume[k];
      for (int s = 0; s < 6; ++s) box_area[6 * k + s] = res.box_area[k][s];
    }
    for (long k = 0; k < m; ++k) {
      const auto& f = res.facets[k];
      fi[k] = f.i;
      fj[k] = f.j;
      farea[k] = f.area;
      for (int a = 0; a < 3; ++a) {
        fnormal[3 * k + a] = f.normal[a];
        fcentroid[3 * k + a] = f.centroid[a];
      }
      if (fvoff) fvoff[k] = f.poly_begin;
    }
    if (fvoff) fvoff[m] = nv;
    if (fverts) std::copy(res.poly.begin(), res.poly.end(), fverts);
    if (stats) {
      stats[0] = res.volume_sum;
      stats[1] = res.max_asymmetry;
      stats[2] = double(res.hidden);
      stats[3] = double(res.empty_cells);
      stats[4] = double(res.dimension);
      stats[5] = double(res.neighbour_pairs);
      stats[6] = double(res.zero_area);
      stats[7] = res.zero_threshold;
      stats[8] = double(res.cap_sorts);
      stats[9] = stats[10] = stats[11] = 0;
    }
    return m;
  } catch (const std::exception& e) {
    return fail(std::string("swd_laguerre_box: ") + e.what());
  } catch (...) {
    return fail("swd_laguerre_box: unknown error");
  }
}

long swd_pair_kinds(long m, const int* aggregate1, const int* aggregate2, int* kind) {
  g_last_error.clear();
  if (m < 0) return fail("swd_pair_kinds: m < 0");
  if (m > 0 && (!aggregate1 || !aggregate2 || !kind)) return fail("swd_pair_kinds: null buffer");
  for (long k = 0; k < m; ++k) {
    swelldem::core::PairMaterial a, b;
    a.aggregateId = aggregate1[k];
    b.aggregateId = aggregate2[k];
    kind[k] = int(swelldem::core::pairKind(a, b));
  }
  return m;
}

}  // extern "C"
