// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/GroundHeight.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "BoxGrid.hpp"
#include "urbanpvs/geometry/city/ConvexClip.hpp"

namespace urbanpvs::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Tri {
  std::array<Vec2, 3> p;
  std::array<double, 3> z;
};

// Barycentric coordinates of q in t (t non-degenerate).
std::array<double, 3> barycentric(const Tri& t, Vec2 q) {
  const double d = cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
  const double l1 = cross(q - t.p[0], t.p[2] - t.p[0]) / d;
  const double l2 = cross(t.p[1] - t.p[0], q - t.p[0]) / d;
  return {1 - l1 - l2, l1, l2};
}

double interpolate(const Tri& t, const std::array<double, 3>& l) {
  return l[0] * t.z[0] + l[1] * t.z[1] + l[2] * t.z[2];
}

Vec2 closest_on_segment(Vec2 q, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double s = len2 > 0 ? std::clamp(dot(q - a, ab) / len2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

double distance_to(const Polygon& poly, Vec2 q) {
  if (inside(poly, q)) return 0;
  double d = kInf;
  for_each_edge(poly, [&](Vec2 a, Vec2 b) { d = std::min(d, distance_to_segment(q, a, b)); });
  return d;
}

// Triangle `t` clipped by the TIN triangle `tin` (Sutherland–Hodgman against its three edges,
// whatever its orientation); empty when they do not overlap.
std::vector<Vec2> clip_triangle(const std::array<Vec2, 3>& t, const Tri& tin) {
  std::vector<Vec2> poly(t.begin(), t.end()), next;
  const double orient = cross(tin.p[1] - tin.p[0], tin.p[2] - tin.p[0]) > 0 ? 1.0 : -1.0;
  for (std::size_t k = 0; k < 3 && !poly.empty(); ++k) {
    const Vec2 a = tin.p[k], b = tin.p[(k + 1) % 3];
    auto side = [&](Vec2 q) { return orient * cross(b - a, q - a); };
    next.clear();
    clip_convex(poly, next, side, [](Vec2 p, Vec2 q, double sp, double sq) {
      return p + (sp / (sp - sq)) * (q - p);
    });
    poly.swap(next);
  }
  return poly;
}

// Calls visit(item) for the items around p, ring by ring, until `done(clearance)` says that
// nothing farther than the clearance can matter.
template <class Visit, class Done>
void ring_search(const detail::BoxGrid& grid, Vec2 p, Visit&& visit, Done&& done) {
  const std::int64_t cx = grid.clamp_x(p.x), cy = grid.clamp_y(p.y);
  const std::int64_t rmax = std::max(grid.columns(), grid.rows());
  for (std::int64_t r = 0; r <= rmax; ++r) {
    grid.for_ring(cx, cy, r, visit);
    const double clearance = grid.ring_clearance(p, cx, cy, r);
    if (done(clearance) || clearance == kInf) return;
  }
}

}  // namespace

struct GroundModel::Impl {
  Source source = Source::Zero;
  std::vector<Tri> terrain;
  std::vector<Polygon> footprints;  // copies: the model may outlive the city
  std::vector<double> footprint_ground;
  bool uniform = false;  // every building stands on the same ground (generated cities)
  detail::BoxGrid grid;

  double terrain_at(Vec2 q) const { return terrain_nearest(q).first; }

  // The terrain's height at q and the distance from q to the TIN (0 inside it).
  std::pair<double, double> terrain_nearest(Vec2 q) const {
    for (std::uint32_t i : grid.at(q)) {
      const auto l = barycentric(terrain[i], q);
      if (l[0] >= -1e-12 && l[1] >= -1e-12 && l[2] >= -1e-12)
        return {interpolate(terrain[i], l), 0.0};
    }
    // Outside the TIN (the margin around the city): the height of its nearest point.
    double best = kInf, z = 0;
    ring_search(
        grid, q,
        [&](std::uint32_t i) {
          const Tri& t = terrain[i];
          Vec2 c = q;
          const auto l = barycentric(t, q);
          if (l[0] < 0 || l[1] < 0 || l[2] < 0) {
            double dc = kInf;
            for (int k = 0; k < 3; ++k) {
              const Vec2 e =
                  closest_on_segment(q, t.p[std::size_t(k)], t.p[std::size_t(k + 1) % 3]);
              const double d = std::hypot(e.x - q.x, e.y - q.y);
              if (d < dc) dc = d, c = e;
            }
          }
          const double d = std::hypot(c.x - q.x, c.y - q.y);
          if (d < best) best = d, z = interpolate(t, barycentric(t, c));
        },
        [&](double clearance) { return best <= clearance; });
    return {z, best};
  }

  // Calls f(item) for every item whose bucket meets `b` (items may repeat).
  template <class F>
  void for_each_near(const Box2& b, F&& f) const {
    for (std::int64_t y = grid.clamp_y(b.min.y); y <= grid.clamp_y(b.max.y); ++y)
      for (std::int64_t x = grid.clamp_x(b.min.x); x <= grid.clamp_x(b.max.x); ++x)
        for (std::uint32_t i : grid.bucket(x, y)) f(i);
  }

  // Inverse-distance weighting of the k nearest footprints: continuous away from buildings, and
  // exactly a building's own ground on its walls, where cells touch it.
  double buildings_at(Vec2 q) const {
    if (uniform) return footprint_ground.front();
    constexpr std::size_t kNearest = 4;
    std::array<std::pair<double, std::uint32_t>, kNearest> best;
    best.fill({kInf, 0});
    ring_search(
        grid, q,
        [&](std::uint32_t i) {
          for (const auto& b : best)
            if (b.second == i && b.first < kInf) return;
          const double d = distance_to(footprints[i], q);
          if (d < best.back().first) {
            best.back() = {d, i};
            std::sort(best.begin(), best.end());
          }
        },
        [&](double clearance) { return best.back().first <= clearance; });
    constexpr double kOnWall = 1e-9;  // m
    if (best.front().first <= kOnWall) {
      double sum = 0;
      int n = 0;
      for (const auto& [d, i] : best)
        if (d <= kOnWall) sum += footprint_ground[i], ++n;
      return sum / n;
    }
    double wsum = 0, zsum = 0;
    for (const auto& [d, i] : best)
      if (d < kInf) {
        const double w = 1 / (d * d);
        wsum += w;
        zsum += w * footprint_ground[i];
      }
    return wsum > 0 ? zsum / wsum : 0.0;
  }
};

std::pair<double, double> GroundModel::range_in(const std::array<Vec2, 3>& t) const {
  double lo = kInf, hi = -kInf;
  for (Vec2 c : t) {
    const double z = at(c);
    lo = std::min(lo, z), hi = std::max(hi, z);
  }
  Box2 box;
  for (Vec2 c : t) box.extend(c);
  const Vec2 centre = (1.0 / 3.0) * (t[0] + t[1] + t[2]);
  double radius = 0;
  for (Vec2 c : t) radius = std::max(radius, std::hypot(c.x - centre.x, c.y - centre.y));
  const Impl& m = *impl_;
  if (m.source == Source::Terrain) {
    // Linear in every TIN triangle, so the extremes over the cell lie at vertices of the TIN
    // triangles that meet it. A corner outside the TIN takes the height of its nearest TIN
    // point; a point of the cell is then within (that distance + the cell's size) of it.
    double reach = 0;
    for (Vec2 c : t) reach = std::max(reach, m.terrain_nearest(c).second);
    const Box2 near = reach > 0 ? box.grown(reach + 2 * radius) : box;
    m.for_each_near(near, [&](std::uint32_t i) {
      const Tri& tin = m.terrain[i];
      Box2 b;
      for (Vec2 v : tin.p) b.extend(v);
      if (!b.overlaps(near)) return;
      if (reach > 0) {  // part of the cell lies outside the TIN: every nearby vertex counts
        for (double z : tin.z) lo = std::min(lo, z), hi = std::max(hi, z);
        return;
      }
      // Over the part of the cell inside this TIN triangle the ground is one plane: its
      // extremes lie at the corners of that part (the cell clipped by the triangle).
      for (Vec2 q : clip_triangle(t, tin)) {
        const double z = interpolate(tin, barycentric(tin, q));
        lo = std::min(lo, z), hi = std::max(hi, z);
      }
    });
  } else if (m.source == Source::Buildings && !m.uniform) {
    // An inverse-distance weighting of the 4 nearest footprints lies between their grounds. The
    // 4 nearest of any point of the cell are within d4(centre) + 2·radius of the centre.
    std::array<double, 4> best;
    best.fill(kInf);
    ring_search(
        m.grid, centre,
        [&](std::uint32_t i) {
          const double d = distance_to(m.footprints[i], centre);
          if (d < best.back()) {
            best.back() = d;
            std::sort(best.begin(), best.end());
          }
        },
        [&](double clearance) { return best.back() <= clearance; });
    const double r = best.back() + 2 * radius;
    if (std::isfinite(r))
      m.for_each_near(box.grown(r), [&](std::uint32_t i) {
        if (distance_to(m.footprints[i], centre) <= r)
          lo = std::min(lo, m.footprint_ground[i]), hi = std::max(hi, m.footprint_ground[i]);
      });
  }
  return {lo, hi};
}

GroundModel::GroundModel(const City& city) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  std::vector<Box2> boxes;
  for (const Triangle3& t : city.terrain.triangles) {
    Tri tri;
    for (std::size_t k = 0; k < 3; ++k) {
      tri.p[k] = {t.v[k][0], t.v[k][1]};
      tri.z[k] = t.v[k][2];
    }
    if (!(std::abs(cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0])) > 0)) continue;
    Box2 b;
    for (Vec2 v : tri.p) b.extend(v);
    m.terrain.push_back(tri);
    boxes.push_back(b);
  }
  if (!m.terrain.empty()) {
    m.source = Source::Terrain;
  } else {
    for (const CityObject& o : city.objects)
      for (const Polygon& p : o.footprint) {
        m.footprints.push_back(p);
        m.footprint_ground.push_back(o.ground_z);
        boxes.push_back(bounds(p));
      }
    if (!m.footprints.empty()) {
      m.source = Source::Buildings;
      m.uniform = std::all_of(m.footprint_ground.begin(), m.footprint_ground.end(),
                              [&](double z) { return z == m.footprint_ground.front(); });
    }
  }
  if (!boxes.empty()) m.grid = detail::BoxGrid(boxes, 2.0);
}

GroundModel::~GroundModel() = default;

double GroundModel::at(Vec2 p) const {
  switch (impl_->source) {
    case Source::Terrain:
      return impl_->terrain_at(p);
    case Source::Buildings:
      return impl_->buildings_at(p);
    case Source::Zero:
      break;
  }
  return 0.0;
}

GroundModel::Source GroundModel::source() const {
  return impl_->source;
}

}  // namespace urbanpvs::geometry
