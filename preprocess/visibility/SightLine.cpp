// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/SightLine.hpp"

#include <algorithm>
#include <limits>

namespace urbanpvs::preprocess {

bool sight_line_blocked(const Vec3& from, const Vec3& to, const BoxQuadtree& tree,
                        std::span<const geometry::Occluder> occluders, double margin,
                        std::uint32_t* blocker) {
  const Vec2 s{from.x, from.y}, d{to.x - from.x, to.y - from.y};
  const double dz = to.z - from.z;
  // The segment's lowest height over the part of it inside a box: nothing lower can block.
  auto lowest_in = [&](const Box2& box, double* height) {
    double t0, t1;
    if (!geometry::clip_line_to_box(s, d, box, 1.0, &t0, &t1)) return false;
    *height = from.z + std::min(t0 * dz, t1 * dz);
    return true;
  };
  auto blocks = [&](const geometry::Occluder& o) {
    double low;
    if (!lowest_in(o.bounds, &low) || !(o.top_high() - margin > low)) return false;
    const double under = o.top_at(s);
    bool cut = false;
    geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
      if (cut || !casts_shadow(a, b, from, under)) return;
      const Vec2 e = b - a;
      const double den = geometry::cross(d, e);
      if (den == 0) return;
      const double t = geometry::cross(a - s, e) / den;  // along the sight line
      const double u = geometry::cross(a - s, d) / den;  // along the wall
      // The wall's top where the line crosses it: linear along a sloped edge (thesis
      // 4.2.1), so exact for any wall.
      if (t > 0 && t < 1 && u >= 0 && u <= 1 && from.z + t * dz < o.top_at(a + u * e) - margin)
        cut = true;
    });
    return cut;
  };
  // Neighbouring sight lines (the pixel centres of one object, seen from one sample) are mostly
  // blocked by the same occluder: asked first, it spares the walk down the tree. Any occluder
  // that blocks proves the line blocked, so the answer is the same whichever is asked first.
  const std::uint32_t tried =
      blocker && *blocker < occluders.size() ? *blocker : std::numeric_limits<std::uint32_t>::max();
  if (tried < occluders.size() && blocks(occluders[tried])) return true;
  bool blocked = false;
  tree.visit(
      [&](std::uint32_t, const BoxQuadtree::Node& n) {
        double low;
        return !blocked && lowest_in(n.box.xy, &low) && n.box.zmax - margin > low;
      },
      [&](std::uint32_t item) {
        if (blocked || item == tried || !blocks(occluders[item])) return;  // tried: not it
        blocked = true;
        if (blocker) *blocker = item;
      });
  return blocked;
}

}  // namespace urbanpvs::preprocess
