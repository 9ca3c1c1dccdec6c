// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/SteppedRoof.hpp"

#include <algorithm>
#include <cmath>

#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

// Levels closer than this (m) become one, the lower: the block stage rounds tops down to 10 cm
// anyway, and each level costs a Boolean operation here and a straight skeleton there.
constexpr double kMergeLevels = 0.05;
// A face rising less than this (m) from its lowest to its highest point counts as flat.
constexpr double kFlat = 0.01;
// Kept between a level and the plane of a sloped face above it (m): rounding of the cut line
// to doubles, far below the occluder shrinking that follows.
constexpr double kPlaneMargin = 0.001;
// Every level above the lowest is inset by this much (m, straight skeleton). Where a roof's
// plan and the ground plan do not share their coordinates exactly (3D BAG rounds to
// millimetres), their difference leaves slivers a few millimetres wide whose needle tips the
// block stage's mitred growth turns into spikes metres long: on the 3D BAG tile, levels of
// 6,000 vertices and minutes of shrinking. The inset removes every part narrower than twice
// it, at 2 cm of each upper level's outline, far below the ε that follows.
constexpr double kLevelInset = 0.02;

// The part of the plane where the face's plane lies below t, as a quadrilateral large enough
// to hold the face's plan: the half-plane slope·(p − origin) < t − z0.
Polygon below_plane(const RoofFace& f, double t) {
  Box2 box;
  for (const Polygon& p : f.plan) box.extend(bounds(p));
  const double g = std::hypot(f.slope.x, f.slope.y);
  const Vec2 u{f.slope.x / g, f.slope.y / g}, v{-u.y, u.x};
  const double s = (t - f.z0) / g;
  double reach = 0;
  for (Vec2 c : {box.min, box.max, Vec2{box.min.x, box.max.y}, Vec2{box.max.x, box.min.y}})
    reach = std::max(reach, std::hypot(c.x - f.origin.x, c.y - f.origin.y));
  const double r = reach + std::abs(s) + 1;
  const Vec2 edge = f.origin + s * u;  // on the line where the plane reaches t
  // Counter-clockwise: along +v on the line, then back along -u, away from the high side.
  return {{edge - r * v, edge + r * v, edge - 2 * r * u + r * v, edge - 2 * r * u - r * v}, {}};
}

// Where the face lies below level h (so a level at h may not cover it).
std::vector<Polygon> lower_than(const RoofFace& f, double h) {
  if (!f.sloped || h + f.deviation + kPlaneMargin >= f.high) return f.plan;
  return intersect_polygons(f.plan, {below_plane(f, h + f.deviation + kPlaneMargin)});
}

}  // namespace

RoofFace roof_face(const std::vector<std::vector<Vec3>>& rings, std::vector<Polygon> plan) {
  RoofFace f;
  f.plan = std::move(plan);
  f.low = std::numeric_limits<double>::infinity();
  f.high = -f.low;
  for (const auto& r : rings)
    for (const Vec3& v : r) f.low = std::min(f.low, v[2]), f.high = std::max(f.high, v[2]);
  const auto& outer = rings.front();
  if (outer.size() < 3 || f.high - f.low < kFlat) return f;
  // Newell's normal and the centroid of the vertices give the plane; the deviation of every
  // vertex from it bounds the surface between them, however a viewer triangulates it.
  Vec3 n{0, 0, 0}, c{0, 0, 0};
  for (std::size_t i = 0; i < outer.size(); ++i) {
    const Vec3& a = outer[i];
    const Vec3& b = outer[(i + 1) % outer.size()];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    c += a;
  }
  c /= static_cast<double>(outer.size());
  const double len = glm::length(n);
  if (len == 0 || std::abs(n[2]) < 0.05 * len) return f;  // steep: counted at its lowest point
  f.origin = {c[0], c[1]};
  f.z0 = c[2];
  f.slope = {-n[0] / n[2], -n[1] / n[2]};
  for (const auto& r : rings)
    for (const Vec3& v : r)
      f.deviation =
          std::max(f.deviation, std::abs(v[2] - f.z0 - dot(Vec2{v[0], v[1]} - f.origin, f.slope)));
  f.sloped = true;
  return f;
}

std::vector<OccluderPrism> stepped_occluders(const std::vector<Polygon>& base, double ground_z,
                                             const std::vector<RoofFace>& faces, double roof_step) {
  std::vector<double> levels;
  for (const RoofFace& f : faces) {
    levels.push_back(f.low);
    if (!f.sloped || roof_step <= 0) continue;
    for (double h = f.low + roof_step; h + f.deviation + kPlaneMargin < f.high; h += roof_step)
      levels.push_back(h);
  }
  std::sort(levels.begin(), levels.end());
  // Each level costs its outline's edges in every cull map that sees it: closer levels merge.
  const double merge = std::max(kMergeLevels, roof_step);
  std::vector<double> kept;
  for (double h : levels)
    if (kept.empty() || h >= kept.back() + merge) kept.push_back(h);

  std::vector<OccluderPrism> out;
  auto emit = [&](const std::vector<Polygon>& region, double top) {
    if (top > ground_z)
      for (const Polygon& p : region) out.push_back({p, ground_z, top});
  };
  emit(base, kept.front());
  if (kept.size() == 1) return out;
  // Above the lowest level, only ground under some face: elsewhere the part's top is unknown.
  std::vector<Polygon> plans;
  for (const RoofFace& f : faces) plans.insert(plans.end(), f.plan.begin(), f.plan.end());
  const std::vector<Polygon> covered = intersect_polygons(base, plans);
  for (std::size_t i = 1; i < kept.size(); ++i) {
    const double h = kept[i];
    std::vector<Polygon> lower;
    for (const RoofFace& f : faces)
      if (f.low < h)
        for (Polygon& p : lower_than(f, h)) lower.push_back(std::move(p));
    std::vector<Polygon> level;
    for (const Polygon& p : subtract_polygons(covered, lower))
      for (Polygon& q : shrink_polygon(p, kLevelInset))
        // The skeleton's output can touch itself where it nearly pinches off; such a piece
        // would crash the block stage's growth (CGAL checks no precondition), so it is
        // dropped: an occluder may always be smaller.
        if (polygon_defect(q).empty()) level.push_back(std::move(q));
    if (level.empty()) break;  // the levels are nested: none above is left either
    emit(level, h);
  }
  return out;
}

}  // namespace urbanpvs::geometry
