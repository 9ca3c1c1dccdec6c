// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/OccluderShadow.hpp"

#include <algorithm>
#include <cmath>

namespace urbanpvs::preprocess {
namespace {

using geometry::cross;

// Keeps the part of a convex polygon where `inside` holds (one Sutherland-Hodgman step).
template <class Inside, class Cut>
std::vector<Vec2> clip_half_plane(const std::vector<Vec2>& poly, Inside inside, Cut cut) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 p = poly[i], q = poly[(i + 1) % poly.size()];
    const bool pin = inside(p), qin = inside(q);
    if (pin) out.push_back(p);
    if (pin != qin) out.push_back(cut(p, q));
  }
  return out;
}

std::vector<Vec2> clip_to_box(std::vector<Vec2> poly, const Box2& box) {
  auto at_x = [](double x) {
    return [x](Vec2 p, Vec2 q) { return Vec2{x, p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x)}; };
  };
  auto at_y = [](double y) {
    return [y](Vec2 p, Vec2 q) { return Vec2{p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y), y}; };
  };
  poly = clip_half_plane(poly, [&](Vec2 p) { return p.x >= box.min.x; }, at_x(box.min.x));
  poly = clip_half_plane(poly, [&](Vec2 p) { return p.x <= box.max.x; }, at_x(box.max.x));
  poly = clip_half_plane(poly, [&](Vec2 p) { return p.y >= box.min.y; }, at_y(box.min.y));
  poly = clip_half_plane(poly, [&](Vec2 p) { return p.y <= box.max.y; }, at_y(box.max.y));
  return poly;
}

}  // namespace

std::optional<OccluderShadow> occluder_shadow(const Vec3& sample, Vec2 a, Vec2 b, double top,
                                              const Box2& clip) {
  if (!faces(a, b, sample)) return std::nullopt;
  const Vec2 v{sample.x, sample.y};
  // The plane through V and the edge's top: normal n = (B - A) x (V - A).
  const Vec2 d = b - a, w = v - a;
  const double dz = sample.z - top;
  const double nx = d.y * dz, ny = -d.x * dz, nz = cross(d, w);
  OccluderShadow s;
  s.a = -nx / nz;
  s.b = -ny / nz;
  s.c = top + (nx * a.x + ny * a.y) / nz;

  // The wedge behind the edge, long enough that its far side lies beyond the clip box.
  double reach = 0;
  for (Vec2 corner : {clip.min, clip.max, Vec2{clip.min.x, clip.max.y}, Vec2{clip.max.x, clip.min.y}})
    reach = std::max(reach, std::hypot(corner.x - v.x, corner.y - v.y));
  const Vec2 va = a - v, vb = b - v;
  const double near = std::min(std::hypot(va.x, va.y), std::hypot(vb.x, vb.y));
  const double stretch = 2 * reach / near + 1;
  std::vector<Vec2> wedge{a, a + stretch * va, b + stretch * vb, b};
  if (geometry::signed_area2(wedge) < 0) std::reverse(wedge.begin(), wedge.end());
  s.polygon = clip_to_box(std::move(wedge), clip);
  if (s.polygon.size() < 3) return std::nullopt;
  return s;
}

}  // namespace urbanpvs::preprocess
