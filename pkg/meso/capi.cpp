// SPDX-License-Identifier: GPL-2.0-or-later
// extern "C" entry points of swelldem_geom (see swelldem_geom.h).
#include "swelldem_geom.h"

#include <exception>
#include <string>

#include "core/PairKind.hpp"
#include "laguerre.hpp"
#include "packing.hpp"

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
