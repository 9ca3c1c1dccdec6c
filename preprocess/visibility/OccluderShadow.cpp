// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/OccluderShadow.hpp"

#include <algorithm>
#include <cmath>

#include "urbanpvs/geometry/city/ConvexClip.hpp"

namespace urbanpvs::preprocess {
namespace {

using geometry::cross;

double signed_area2(const ShadowPolygon& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return a;
}

// The part of a convex polygon inside `box`. A cut point lies exactly on the box's side (its
// other coordinate interpolated): the rasterizer's rows and columns start there.
ShadowPolygon clip_to_box(ShadowPolygon poly, const Box2& box) {
  auto at_x = [](double x) {
    return [x](Vec2 p, Vec2 q, double, double) {
      return Vec2{x, p.y + (q.y - p.y) * (x - p.x) / (q.x - p.x)};
    };
  };
  auto at_y = [](double y) {
    return [y](Vec2 p, Vec2 q, double, double) {
      return Vec2{p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y), y};
    };
  };
  auto keep = [&poly](auto side, auto cut) {
    ShadowPolygon out;
    geometry::clip_convex(poly, out, side, cut);
    poly = out;
  };
  keep([&](Vec2 p) { return p.x - box.min.x; }, at_x(box.min.x));
  keep([&](Vec2 p) { return box.max.x - p.x; }, at_x(box.max.x));
  keep([&](Vec2 p) { return p.y - box.min.y; }, at_y(box.min.y));
  keep([&](Vec2 p) { return box.max.y - p.y; }, at_y(box.max.y));
  return poly;
}

}  // namespace

std::optional<OccluderShadow> occluder_shadow(const Vec3& sample, Vec2 a, double top_a, Vec2 b,
                                              double top_b, double top_under_sample,
                                              const Box2& clip) {
  if (!casts_shadow(a, b, sample, top_under_sample)) return std::nullopt;
  const Vec2 v{sample.x, sample.y};
  // The plane through V and the edge's top, A' = (a, top_a) to B' = (b, top_b): normal
  // n = (B' - A') x (V - A'). A flat edge takes the shorter form, so that its plane is the
  // same to the last bit as before sloped edges existed.
  const Vec2 d = b - a, w = v - a;
  const double dz = sample.z - top_a, rise = top_b - top_a;
  const double nx = rise == 0 ? d.y * dz : d.y * dz - rise * w.y;
  const double ny = rise == 0 ? -d.x * dz : rise * w.x - d.x * dz;
  const double nz = cross(d, w);
  OccluderShadow s;
  s.a = -nx / nz;
  s.b = -ny / nz;
  s.c = top_a + (nx * a.x + ny * a.y) / nz;

  // The wedge behind the edge out to radius R beyond every corner of the clip box. Its far side
  // must not be the chord between the rays through a and b: seen at a grazing angle (a street
  // seen along its walls) the wedge opens to nearly 180° and that chord passes close to the
  // sample, cutting off most of the shadow. Two tangent segments per half-angle (each < 90°,
  // so 1/cos <= √2) bound the circular arc of radius R instead.
  double reach = 0;
  for (Vec2 corner :
       {clip.min, clip.max, Vec2{clip.min.x, clip.max.y}, Vec2{clip.max.x, clip.min.y}})
    reach = std::max(reach, std::hypot(corner.x - v.x, corner.y - v.y));
  reach = std::max({reach, std::hypot(a.x - v.x, a.y - v.y), std::hypot(b.x - v.x, b.y - v.y)});
  const double R = 1.01 * reach + 1;
  auto unit = [](Vec2 p) { return (1 / std::hypot(p.x, p.y)) * p; };
  const Vec2 ua = unit(a - v), ub = unit(b - v), um = unit(ua + ub);
  const Vec2 ta = unit(ua + um), tb = unit(um + ub);
  const double cos_quarter = std::hypot(ua.x + um.x, ua.y + um.y) / 2;  // cos(θ/4) >= √2/2
  ShadowPolygon wedge{
      a, v + R * ua, v + (R / cos_quarter) * ta, v + (R / cos_quarter) * tb, v + R * ub, b};
  if (signed_area2(wedge) < 0) std::reverse(wedge.begin(), wedge.end());
  s.polygon = clip_to_box(std::move(wedge), clip);
  if (s.polygon.size() < 3) return std::nullopt;
  return s;
}

}  // namespace urbanpvs::preprocess
