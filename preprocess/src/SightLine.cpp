// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/SightLine.hpp"

#include <algorithm>
#include <limits>

namespace urbanpvs::preprocess {
namespace {

// The part [t0, t1] of the segment from + t·d (t in [0, 1]) inside `box`; false when none.
bool clip_to_box(Vec2 from, Vec2 d, const Box2& box, double* t0, double* t1) {
  *t0 = 0;
  *t1 = 1;
  auto slab = [&](double o, double dv, double lo, double hi) {
    if (dv == 0) return lo <= o && o <= hi;
    double a = (lo - o) / dv, b = (hi - o) / dv;
    if (a > b) std::swap(a, b);
    *t0 = std::max(*t0, a);
    *t1 = std::min(*t1, b);
    return *t0 <= *t1;
  };
  return slab(from.x, d.x, box.min.x, box.max.x) && slab(from.y, d.y, box.min.y, box.max.y);
}

}  // namespace

bool sight_line_blocked(const Vec3& from, const Vec3& to, const BoxQuadtree& tree,
                        std::span<const geometry::Occluder> occluders, double margin) {
  const Vec2 s{from.x, from.y}, d{to.x - from.x, to.y - from.y};
  const double dz = to.z - from.z;
  // The segment's lowest height over the part of it inside a box: nothing lower can block.
  auto lowest_in = [&](const Box2& box, double* height) {
    double t0, t1;
    if (!clip_to_box(s, d, box, &t0, &t1)) return false;
    *height = from.z + std::min(t0 * dz, t1 * dz);
    return true;
  };
  bool blocked = false;
  tree.visit(
      [&](std::uint32_t, const BoxQuadtree::Node& n) {
        double low;
        return !blocked && lowest_in(n.box.xy, &low) && n.box.zmax - margin > low;
      },
      [&](std::uint32_t item) {
        if (blocked) return;
        const geometry::Occluder& o = occluders[item];
        double low;
        if (!lowest_in(o.bounds, &low) || !(o.top_z - margin > low)) return;
        geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
          if (blocked) return;
          const Vec2 e = b - a;
          const double den = geometry::cross(d, e);
          if (den == 0) return;
          const double t = geometry::cross(a - s, e) / den;  // along the sight line
          const double u = geometry::cross(a - s, d) / den;  // along the wall
          if (t > 0 && t < 1 && u >= 0 && u <= 1 && from.z + t * dz < o.top_z - margin)
            blocked = true;
        });
      });
  return blocked;
}

}  // namespace urbanpvs::preprocess
