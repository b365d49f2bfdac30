// SPDX-License-Identifier: GPL-2.0-or-later
//
// Constructive advancing-front packing of discs in the rectangle [0,W]x[0,H].
//
// The front is an ordered chain of objects, from the left side of the box to its
// right side: LEFT, (discs and possibly FLOOR), RIGHT. The empty part of the box
// lies on the left of the chain when it is walked from LEFT to RIGHT. Every new
// disc is placed tangent to two consecutive objects (A, B) of the chain, on the
// empty side, and is inserted between them. The pair chosen next is the one
// whose candidate centre is lowest, so the packing grows in layers from the
// bottom side. When the candidate overlaps an object C of the chain (a disc or
// a side of the box), the chain between the pair and C is dropped (those
// objects become interior) and the placement is retried on the new pair. A last
// pass places discs tangent to the top side. Radii are uniform in [rmin, rmax];
// a radius is only enlarged (never beyond rmax) when a front gap is wider than
// the disc drawn for it.
#include "packing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>

namespace swelldem { namespace meso {

namespace {

constexpr int kLeft = -1, kFloor = -2, kRight = -3;
constexpr int kNoHit = -1000;  // no overlap (not an object id)

// Small, portable generator: splitmix64 seeding + xoshiro256** (so the same seed
// gives the same packing with any standard library).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (auto& w : s_) {
      seed += 0x9E3779B97F4A7C15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
      w = z ^ (z >> 31);
    }
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }

 private:
  static std::uint64_t rotl(std::uint64_t v, int k) { return (v << k) | (v >> (64 - k)); }
  std::uint64_t s_[4];
};

struct Node {
  int obj;        // disc index >= 0 or kLeft / kFloor / kRight
  int prev, next; // node indices, -1 at the ends
  bool alive;
  unsigned version;  // bumped when `next` changes or the node dies
};

struct HeapEntry {
  double key;
  int node;
  unsigned version;
  bool operator<(const HeapEntry& o) const {  // min-heap on key, ties on node index
    if (key != o.key) return key > o.key;
    return node > o.node;
  }
};

class Packer {
 public:
  Packer(double W, double H, double rmin, double rmax, std::uint64_t seed)
      : W_(W), H_(H), rmin_(rmin), rmax_(rmax), rng_(seed) {
    cell_ = 2.0 * rmax_;
    nx_ = std::max(1, int(std::ceil(W_ / cell_)));
    ny_ = std::max(1, int(std::ceil(H_ / cell_)));
    grid_.assign(std::size_t(nx_) * ny_, {});
    tol_ = 1e-10 * rmax_;
  }

  Packing run() {
    // Initial chain: LEFT, FLOOR, RIGHT.
    int nl = new_node(kLeft), nf = new_node(kFloor), nr = new_node(kRight);
    link(nl, nf);
    link(nf, nr);
    push_pair(nl);
    push_pair(nf);
    double r = draw_radius();
    while (!heap_.empty()) {
      HeapEntry e = heap_.top();
      heap_.pop();

      const Node& nd = nodes_[e.node];
      if (!nd.alive || nd.version != e.version || nd.next < 0) continue;
      if (place_on_pair(e.node, r)) r = draw_radius();
    }
    top_fill();
    Packing out;
    out.x = X_;
    out.y = Y_;
    out.r = R_;
    double area = 0;
    for (double ri : R_) area += M_PI * ri * ri;
    stats_.density = area / (W_ * H_);
    stats_.max_overlap_rel = final_overlap_check() / rmax_;
    out.stats = stats_;
    return out;
  }

 private:
  double W_, H_, rmin_, rmax_;
  Rng rng_;
  double cell_, tol_;
  int nx_, ny_;
  std::vector<std::vector<int>> grid_;
  std::vector<double> X_, Y_, R_;
  std::vector<int> disc_node_;  // front node of each disc, -1 if interior
  std::vector<Node> nodes_;
  std::priority_queue<HeapEntry> heap_;
  PackingStats stats_;
  int floor_node_ = -1;

  double draw_radius() { return rmin_ + (rmax_ - rmin_) * rng_.uniform(); }

  int new_node(int obj) {
    nodes_.push_back(Node{obj, -1, -1, true, 0});
    int id = int(nodes_.size()) - 1;
    if (obj >= 0) disc_node_[obj] = id;
    if (obj == kFloor) floor_node_ = id;
    return id;
  }
  void link(int a, int b) {
    nodes_[a].next = b;
    nodes_[a].version++;
    nodes_[b].prev = a;
  }
  void kill(int nidx) {
    Node& nd = nodes_[nidx];
    nd.alive = false;
    nd.version++;
    if (nd.obj >= 0) disc_node_[nd.obj] = -1;
    if (nd.obj == kFloor) floor_node_ = -1;
  }

  // Smallest radius for which a disc tangent to both objects exists.
  double required_radius(int a, int b) const {
    if (a >= 0 && b >= 0) {
      double d = std::hypot(X_[b] - X_[a], Y_[b] - Y_[a]);
      return 0.5 * (d - R_[a] - R_[b]);
    }
    if (a == kLeft && b >= 0) return 0.5 * (X_[b] - R_[b]);
    if (a >= 0 && b == kRight) return 0.5 * (W_ - X_[a] - R_[a]);
    if (a >= 0 && b == kFloor) return 0.5 * (Y_[a] - R_[a]);
    if (a == kFloor && b >= 0) return 0.5 * (Y_[b] - R_[b]);
    if (a == kLeft && b == kRight) return 0.5 * W_;
    return 0.0;  // LEFT-FLOOR, FLOOR-RIGHT corners
  }

  // The other leg of a right triangle with hypotenuse hyp and leg side; a leg
  // that is imaginary by round-off only counts as 0. False when it does not exist.
  static bool other_leg(double hyp, double side, double& leg) {
    double h2 = hyp * hyp - side * side;
    if (h2 < 0) {
      if (h2 < -1e-12 * hyp * hyp) return false;
      h2 = 0;
    }
    leg = std::sqrt(h2);
    return true;
  }

  // Centre of the disc of radius rr tangent to objects a then b, on the empty
  // side of the chain. Returns false when it does not exist.
  bool candidate(int a, int b, double rr, double& px, double& py) const {
    if (a >= 0 && b >= 0) {
      double dx = X_[b] - X_[a], dy = Y_[b] - Y_[a];
      double d = std::hypot(dx, dy);
      if (d <= 0) return false;
      double la = R_[a] + rr, lb = R_[b] + rr;
      double t = (la * la - lb * lb + d * d) / (2 * d);
      double h;
      if (!other_leg(la, t, h)) return false;
      double ux = dx / d, uy = dy / d;
      px = X_[a] + t * ux - h * uy;
      py = Y_[a] + t * uy + h * ux;
      return true;
    }
    auto vertical = [&](double xc, int d, double& ox, double& oy) {
      // centre on the line x = xc, tangent to disc d, above it
      double h;
      if (!other_leg(R_[d] + rr, xc - X_[d], h)) return false;
      ox = xc;
      oy = Y_[d] + h;
      return true;
    };
    auto horizontal = [&](int d, double sign, double& ox, double& oy) {
      // centre on the line y = rr, tangent to disc d, on side `sign` of it
      double h;
      if (!other_leg(R_[d] + rr, rr - Y_[d], h)) return false;
      ox = X_[d] + sign * h;
      oy = rr;
      return true;
    };
    if (a == kLeft && b >= 0) return vertical(rr, b, px, py);
    if (a >= 0 && b == kRight) return vertical(W_ - rr, a, px, py);
    if (a >= 0 && b == kFloor) return horizontal(a, +1.0, px, py);
    if (a == kFloor && b >= 0) return horizontal(b, -1.0, px, py);
    if (a == kLeft && b == kFloor) { px = rr; py = rr; return true; }
    if (a == kFloor && b == kRight) { px = W_ - rr; py = rr; return true; }
    return false;  // LEFT-RIGHT: nothing left to fill between the two sides
  }

  void push_pair(int nidx) {
    const Node& nd = nodes_[nidx];
    if (!nd.alive || nd.next < 0) return;
    int a = nd.obj, b = nodes_[nd.next].obj;
    double rr = std::max(0.5 * (rmin_ + rmax_), required_radius(a, b));
    if (rr > rmax_ * (1 + 1e-12)) return;  // gap too wide: abandoned
    double px, py;
    if (!candidate(a, b, rr, px, py)) return;
    heap_.push(HeapEntry{py, nidx, nd.version});
  }

  void grid_range(double x, double y, double reach, int& i0, int& i1, int& j0, int& j1) const {
    i0 = std::max(0, int(std::floor((x - reach) / cell_)));
    i1 = std::min(nx_ - 1, int(std::floor((x + reach) / cell_)));
    j0 = std::max(0, int(std::floor((y - reach) / cell_)));
    j1 = std::min(ny_ - 1, int(std::floor((y + reach) / cell_)));
  }

  // Disc overlapping (x, y, rr) most deeply, or -1.
  int deepest_overlap(double x, double y, double rr) const {
    int i0, i1, j0, j1, best = -1;
    double best_depth = tol_;
    grid_range(x, y, rr + rmax_, i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        for (int k : grid_[std::size_t(j) * nx_ + i]) {
          double depth = R_[k] + rr - std::hypot(X_[k] - x, Y_[k] - y);
          if (depth > best_depth) { best_depth = depth; best = k; }
        }
    return best;
  }

  int add_disc(double x, double y, double rr) {
    // Defensive: the disc area can never exceed the box area.
    if (double(R_.size()) > W_ * H_ / (M_PI * rmin_ * rmin_) + 16)
      throw std::logic_error("packing produced more discs than can fit; internal error");
    if (!(x - rr >= -tol_ && x + rr <= W_ + tol_ && y - rr >= -tol_ && y + rr <= H_ + tol_))
      throw std::logic_error("packing placed a disc outside the box; internal error");
    X_.push_back(x);
    Y_.push_back(y);
    R_.push_back(rr);
    disc_node_.push_back(-1);
    int id = int(R_.size()) - 1;
    int i = std::min(nx_ - 1, std::max(0, int(std::floor(x / cell_))));
    int j = std::min(ny_ - 1, std::max(0, int(std::floor(y / cell_))));
    grid_[std::size_t(j) * nx_ + i].push_back(id);
    return id;
  }

  // Walk the chain from node `from` in direction dir (+1 next, -1 prev) looking
  // for the node of object obj; returns the node or -1.
  int find_on_chain(int from, int obj, int dir) const {
    int k = from;
    while (k >= 0) {
      if (nodes_[k].obj == obj) return k;
      k = dir > 0 ? nodes_[k].next : nodes_[k].prev;
    }
    return -1;
  }

  // Removes the nodes strictly between na and nb (na before nb).
  void cut_between(int na, int nb) {
    int k = nodes_[na].next;
    while (k != nb) {
      int nxt = nodes_[k].next;
      kill(k);
      k = nxt;
    }
    link(na, nb);
  }

  bool place_on_pair(int na, double r) {
    int nb = nodes_[na].next;
    for (int iter = 0; iter < 100000; ++iter) {
      int a = nodes_[na].obj, b = nodes_[nb].obj;
      double req = required_radius(a, b);
      double rr = r;
      if (req > rr) {
        if (req > rmax_ * (1 + 1e-12)) { stats_.abandoned++; return false; }
        rr = std::min(rmax_, req * (1 + 1e-12));
      }
      double px, py;
      if (!candidate(a, b, rr, px, py)) { stats_.abandoned++; return false; }
      if (py + rr > H_ + tol_) {
        // Does not fit under the top side: try the smallest admissible disc.
        double r2 = std::max(rmin_, std::min(rmax_, req * (1 + 1e-12)));
        if (r2 < rr && candidate(a, b, r2, px, py) && py + r2 <= H_ + tol_) {
          rr = r2;
        } else {
          return false;  // left for the top-fill pass
        }
      }
      int hit = kNoHit;  // object to collapse the chain onto
      if (px - rr < -tol_) hit = kLeft;
      else if (px + rr > W_ + tol_) hit = kRight;
      else if (py - rr < -tol_) hit = kFloor;
      else {
        int k = deepest_overlap(px, py, rr);
        if (k >= 0) hit = k;
      }
      if (hit == kNoHit) {
        int id = add_disc(px, py, rr);
        if (rr > r) stats_.enlarged++;
        int nn = new_node(id);
        link(na, nn);
        link(nn, nb);
        push_pair(na);
        push_pair(nn);
        return true;
      }
      stats_.collapses++;
      if (hit == a || hit == b) { stats_.abandoned++; return false; }
      int fwd = find_on_chain(nb, hit, +1);
      if (fwd >= 0) { cut_between(na, fwd); nb = fwd; continue; }
      int bwd = find_on_chain(na, hit, -1);
      if (bwd >= 0) { cut_between(bwd, nb); na = bwd; continue; }
      stats_.abandoned++;  // overlap with an interior disc: give this pair up
      return false;
    }
    stats_.abandoned++;
    return false;
  }

  bool try_add(double px, double py, double rr) {
    if (px - rr < -tol_ || px + rr > W_ + tol_ || py - rr < -tol_ || py + rr > H_ + tol_) return false;
    if (deepest_overlap(px, py, rr) >= 0) return false;
    add_disc(px, py, rr);
    stats_.top_fill++;
    return true;
  }

  // Discs tangent to the top side and to one disc near it, largest that fits first.
  void top_fill() {
    std::vector<int> near;
    for (std::size_t k = 0; k < R_.size(); ++k)
      if (Y_[k] + R_[k] > H_ - 4 * rmax_) near.push_back(int(k));
    std::sort(near.begin(), near.end(), [&](int p, int q) { return X_[p] < X_[q]; });
    const int nr = 4;
    for (int pass = 0; pass < 2; ++pass) {
      for (int d : near) {
        for (int side = -1; side <= 1; side += 2) {
          for (int s = 0; s < nr; ++s) {
            double rr = rmax_ - (rmax_ - rmin_) * s / (nr - 1);
            double yc = H_ - rr, l = R_[d] + rr, dy = yc - Y_[d];
            double h2 = l * l - dy * dy;
            if (h2 < 0) continue;
            if (try_add(X_[d] + side * std::sqrt(h2), yc, rr)) break;
          }
        }
      }
      // the two top corners
      for (int s = 0; s < nr; ++s) {
        double rr = rmax_ - (rmax_ - rmin_) * s / (nr - 1);
        if (try_add(rr, H_ - rr, rr)) break;
      }
      for (int s = 0; s < nr; ++s) {
        double rr = rmax_ - (rmax_ - rmin_) * s / (nr - 1);
        if (try_add(W_ - rr, H_ - rr, rr)) break;
      }
    }
  }

  double final_overlap_check() const {
    double worst = 0;
    for (std::size_t k = 0; k < R_.size(); ++k) {
      int i0, i1, j0, j1;
      grid_range(X_[k], Y_[k], R_[k] + rmax_, i0, i1, j0, j1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          for (int m : grid_[std::size_t(j) * nx_ + i]) {
            if (m <= int(k)) continue;
            double depth = R_[k] + R_[m] - std::hypot(X_[k] - X_[m], Y_[k] - Y_[m]);
            worst = std::max(worst, depth);
          }
    }
    return worst;
  }
};

}  // namespace

Packing pack_rectangle(double width, double height, double rmin, double rmax, std::uint64_t seed) {
  auto bad = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!(std::isfinite(width) && width > 0)) bad("width must be finite and > 0");
  if (!(std::isfinite(height) && height > 0)) bad("height must be finite and > 0");
  if (!(std::isfinite(rmax) && rmax > 0)) bad("rmax must be finite and > 0");
  if (!(std::isfinite(rmin) && rmin > 0 && rmin <= rmax)) bad("rmin must be in (0, rmax]");
  if (2 * rmax > std::min(width, height)) bad("2 rmax must not exceed min(width, height)");
  if (width * height / (rmin * rmin) > 4e8) bad("too many discs (W H / rmin^2 > 4e8)");
  Packer p(width, height, rmin, rmax, seed);
  return p.run();
}

}}  // namespace swelldem::meso
