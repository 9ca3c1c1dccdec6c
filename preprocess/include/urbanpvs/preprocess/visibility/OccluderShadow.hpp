// SPDX-License-Identifier: GPL-3.0-or-later
// The occluder shadow of thesis 4.2.1: seen from a sample point V, the top edge of a wall hides
// everything behind it that lies below the plane through V and that edge. Over the ground the
// shadow is the (convex) wedge behind the edge, with its height given by that plane.
#pragma once

#include <array>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::preprocess {

using geometry::Box2;
using geometry::Vec2;
using geometry::Vec3;

/// A convex polygon of a shadow, stored inline: shadows are made by the ten thousand per cell
/// and must not touch the heap. Clipping a convex polygon by a half-plane adds at most one
/// corner: a wedge has 6, the clip box adds at most 4: <= 10.
class ShadowPolygon {
 public:
  static constexpr std::size_t kCapacity = 16;
  ShadowPolygon() = default;
  ShadowPolygon(std::initializer_list<Vec2> corners) {
    for (Vec2 c : corners) push_back(c);
  }
  void push_back(Vec2 c) {
    if (size_ == kCapacity)
      throw std::logic_error("ShadowPolygon: more corners than convex allows");
    corners_[size_++] = c;
  }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const Vec2& operator[](std::size_t i) const { return corners_[i]; }
  Vec2& operator[](std::size_t i) { return corners_[i]; }
  const Vec2* begin() const { return corners_.data(); }
  const Vec2* end() const { return corners_.data() + size_; }
  Vec2* begin() { return corners_.data(); }
  Vec2* end() { return corners_.data() + size_; }

 private:
  std::array<Vec2, kCapacity> corners_{};
  std::size_t size_ = 0;
};

struct OccluderShadow {
  ShadowPolygon polygon;       ///< convex, counter-clockwise, clipped to the requested box
  double a = 0, b = 0, c = 0;  ///< height over the ground: z = a·x + b·y + c

  double height(Vec2 p) const { return a * p.x + b * p.y + c; }
};

/// True when the edge a→b of a ring that has its region on the left (counter-clockwise outer
/// ring, clockwise hole) faces `sample`: from a sample below the occluder's top, only such
/// edges cast shadows that are not already covered by the shadows of the ring's other edges
/// (thesis 4.3.2, back-face culling).
inline bool faces(Vec2 a, Vec2 b, const Vec3& sample) {
  return geometry::cross(b - a, Vec2{sample.x, sample.y} - a) < 0;
}

/// Whether the wall over a→b of an occluder with top `top` casts a shadow from `sample`: when
/// it faces the sample, and every wall when the sample is above the top. A line from above
/// that comes down through the top leaves the occluder through a wall facing away, below its
/// top, and nothing of a front wall's shadow says so: a low building seen from a hill, a
/// terrain level the cell stands on (TerrainOccluders.hpp). The maps and the exact sight lines
/// both use this rule, so they judge alike.
inline bool casts_shadow(Vec2 a, Vec2 b, const Vec3& sample, double top) {
  return sample.z > top || faces(a, b, sample);
}

/// The shadow of the wall over edge a→b with top height `top`, seen from `sample`, clipped by us
/// to `clip` (never left to a rasterizer's clipping, which is not exact at the border). Nothing
/// when the wall casts no shadow from the sample (casts_shadow) or the wedge misses `clip`.
std::optional<OccluderShadow> occluder_shadow(const Vec3& sample, Vec2 a, Vec2 b, double top,
                                              const Box2& clip);

}  // namespace urbanpvs::preprocess
