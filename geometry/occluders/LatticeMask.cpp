// SPDX-License-Identifier: GPL-3.0-or-later
#include "LatticeMask.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace urbanpvs::geometry {
namespace {

/// True when the ring's first point lies on the straight line from its last to its second.
bool leaving_direction_matches(const Ring& r) {
  const Vec2 a = r.back(), b = r.front(), c = r[1];
  return (a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y);
}

}  // namespace

LatticeMask::LatticeMask(std::vector<double> xs, std::vector<double> ys)
    : xs_(std::move(xs)),
      ys_(std::move(ys)),
      nu_(static_cast<int>(xs_.size()) - 1),
      nv_(static_cast<int>(ys_.size()) - 1) {
  in_.assign(
      static_cast<std::size_t>(std::max(nu_, 0)) * static_cast<std::size_t>(std::max(nv_, 0)), 0);
}

bool LatticeMask::full() const {
  return std::all_of(in_.begin(), in_.end(), [](unsigned char c) { return c != 0; });
}

void LatticeMask::separate_diagonals() {
  for (bool changed = true; changed;) {
    changed = false;
    for (int v = 0; v + 1 < nv_; ++v)
      for (int u = 0; u + 1 < nu_; ++u) {
        const bool a = get(u, v), b = get(u + 1, v), c = get(u, v + 1), d = get(u + 1, v + 1);
        if (a && d && !b && !c) {
          set(u, v, false);
          changed = true;
        } else if (b && c && !a && !d) {
          set(u + 1, v, false);
          changed = true;
        }
      }
  }
}

bool LatticeMask::polygons(std::vector<Polygon>& out) const {
  // The boundary edge leaving each lattice vertex, with the set cells on its left: after
  // separate_diagonals, at most one. 0: +x, 1: +y, 2: -x, 3: -y; 4: none.
  const auto w = static_cast<std::size_t>(nu_ + 1);
  std::vector<unsigned char> leaving(w * static_cast<std::size_t>(nv_ + 1), 4);
  auto vertex = [&](int u, int v) -> unsigned char& {
    return leaving[static_cast<std::size_t>(v) * w + static_cast<std::size_t>(u)];
  };
  bool ok = true;
  auto put = [&](int u, int v, unsigned char dir) {
    ok = ok && vertex(u, v) == 4;
    vertex(u, v) = dir;
  };
  for (int v = 0; v < nv_; ++v)
    for (int u = 0; u < nu_; ++u) {
      if (!get(u, v)) continue;
      if (v == 0 || !get(u, v - 1)) put(u, v, 0);
      if (u + 1 == nu_ || !get(u + 1, v)) put(u + 1, v, 1);
      if (v + 1 == nv_ || !get(u, v + 1)) put(u + 1, v + 1, 2);
      if (u == 0 || !get(u - 1, v)) put(u, v + 1, 3);
    }
  if (!ok) return false;
  static constexpr int kStep[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  std::vector<Ring> outers, holes;
  for (int v0 = 0; v0 <= nv_; ++v0)
    for (int u0 = 0; u0 <= nu_; ++u0) {
      if (vertex(u0, v0) == 4) continue;
      Ring ring;
      int u = u0, v = v0, previous = -1;
      for (;;) {
        unsigned char& slot = vertex(u, v);
        if (slot == 4) break;  // back at the start
        const int dir = slot;
        slot = 4;
        if (dir != previous) ring.push_back(point(u, v));  // a corner
        previous = dir;
        u += kStep[dir][0];
        v += kStep[dir][1];
      }
      if (u != u0 || v != v0 || ring.size() < 4) return false;
      // The start may sit mid-edge when the walk began on a straight run: drop it.
      if (leaving_direction_matches(ring)) ring.erase(ring.begin());
      (signed_area2(ring) > 0 ? outers : holes).push_back(std::move(ring));
    }
  const std::size_t first = out.size();
  for (Ring& r : outers) out.push_back({std::move(r), {}});
  for (Ring& h : holes) {
    // Each hole in the smallest outer ring around it (islands nest in holes).
    std::size_t best = out.size();
    double best_area = std::numeric_limits<double>::infinity();
    for (std::size_t k = first; k < out.size(); ++k) {
      const double a = signed_area2(out[k].outer);
      if (a < best_area && inside_ring(out[k].outer, h.front())) best = k, best_area = a;
    }
    if (best == out.size()) return false;
    out[best].holes.push_back(std::move(h));
  }
  return true;
}

}  // namespace urbanpvs::geometry
