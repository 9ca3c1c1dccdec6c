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
#include "urbanpvs/geometry/occluders/Occluder.hpp"

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

/// Whether the wall over a→b of an occluder casts a shadow from `sample`: when it faces the
/// sample, and every wall when the sample is above the occluder's top (`top_under_sample`: the
/// height of the top's plane at the sample's x, y). A line from above that comes down through
/// the top leaves the occluder through a wall facing away, below its top, and nothing of a
/// front wall's shadow says so: a low building seen from a hill, a terrain level the cell stands
/// on (TerrainOccluders.hpp). From below the plane no line enters through the top (a line
/// crosses a plane once), so there the facing walls' shadows hold every other wall's. The maps
/// and the exact sight lines both use this rule, so they judge alike.
inline bool casts_shadow(Vec2 a, Vec2 b, const Vec3& sample, double top_under_sample) {
  return sample.z > top_under_sample || faces(a, b, sample);
}

/// The shadow of the wall over edge a→b whose top runs from height `top_a` over a to `top_b`
/// over b, seen from `sample`: the wedge behind the edge, below the plane through the sample and
/// the top edge (thesis 4.2.1; for a sloped edge the plane tilts with it). Clipped by us to
/// `clip` (never left to a rasterizer's clipping, which is not exact at the border). Nothing
/// when the wall casts no shadow from the sample (casts_shadow, given `top_under_sample`) or the
/// wedge misses `clip`.
std::optional<OccluderShadow> occluder_shadow(const Vec3& sample, Vec2 a, double top_a, Vec2 b,
                                              double top_b, double top_under_sample,
                                              const Box2& clip);

/// The shadow of a wall with a flat top at `top`.
inline std::optional<OccluderShadow> occluder_shadow(const Vec3& sample, Vec2 a, Vec2 b, double top,
                                                     const Box2& clip) {
  return occluder_shadow(sample, a, top, b, top, top, clip);
}

/// Calls `f(shadow)` for the shadow of every wall of `o` that casts one from `sample` within
/// `clip`: what one sample's cull map holds of one occluder, in whichever renderer.
template <class F>
void for_each_shadow(const Vec3& sample, const geometry::Occluder& o, const Box2& clip, F&& f) {
  const double under = o.top_at({sample.x, sample.y});
  geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
    if (auto s = occluder_shadow(sample, a, o.top_at(a), b, o.top_at(b), under, clip)) f(*s);
  });
}

}  // namespace urbanpvs::preprocess
