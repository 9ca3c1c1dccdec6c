// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CullMapHorizon.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace urbanpvs::preprocess {
namespace {

std::array<Vec2, 4> corners(const Box2& b) {
  return {b.min, Vec2{b.max.x, b.min.y}, b.max, Vec2{b.min.x, b.max.y}};
}

// Distance between two disjoint-or-not boxes (0 when they overlap).
double box_distance(const Box2& a, const Box2& b) {
  const double dx = std::max({0.0, a.min.x - b.max.x, b.min.x - a.max.x});
  const double dy = std::max({0.0, a.min.y - b.max.y, b.min.y - a.max.y});
  return std::hypot(dx, dy);
}

// Largest distance from a point of `a` to a point of `b`.
double box_reach(const Box2& a, const Box2& b) {
  const double dx = std::max(a.max.x - b.min.x, b.max.x - a.min.x);
  const double dy = std::max(a.max.y - b.min.y, b.max.y - a.min.y);
  return std::hypot(dx, dy);
}

// Where the convex hull of `points` meets the line {axis = at}: the interval of the other
// coordinate, or nothing. The hull's extreme points on the line lie on segments between two of
// the points, so trying every pair is exact.
template <std::size_t N>
std::optional<std::pair<double, double>> hull_on_line(const std::array<Vec2, N>& points, int axis,
                                                      double at) {
  auto along = [axis](Vec2 p) { return axis == 0 ? p.x : p.y; };
  auto across = [axis](Vec2 p) { return axis == 0 ? p.y : p.x; };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = i; j < N; ++j) {
      const double a = along(points[i]) - at, b = along(points[j]) - at;
      if (a * b > 0) continue;
      double v;
      if (a == b) {
        v = across(points[i]);  // a == b == 0: both on the line
        lo = std::min({lo, v, across(points[j])});
        hi = std::max({hi, v, across(points[j])});
        continue;
      }
      v = across(points[i]) + (across(points[j]) - across(points[i])) * (a / (a - b));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (!(lo <= hi)) return std::nullopt;
  return std::pair{lo, hi};
}

}  // namespace

bool hidden_behind_horizon(const CullMap& map, const CellBox& cell, const geometry::Box3& box) {
  const CullMapGrid& g = map.grid();
  if (box.xy.empty() || !outside_map(g, box.xy) || !inside_map(g, cell.xy)) return false;
  // Along a sight line from a viewpoint c (height <= cell.top) to a point o of the box (height
  // <= box.zmax), the height at the border crossing b is at most
  //   cell.top + max(0, box.zmax - cell.top) · |b - c| / |o - c|,
  // and |b - c| <= reach(pixel of b, cell), |o - c| >= distance(cell, box): the top supporting
  // plane of the view channel, bounded per border pixel.
  const double gap = box_distance(cell.xy, box.xy);
  if (!(gap > 0)) return false;
  const double rise = std::max(0.0, box.zmax - cell.top) / gap;
  std::array<Vec2, 8> hull{};
  const auto a = corners(cell.xy), b = corners(box.xy);
  std::copy(a.begin(), a.end(), hull.begin());
  std::copy(b.begin(), b.end(), hull.begin() + 4);

  const Box2 m = g.bounds();
  // The four sides: (axis of the side's line, its coordinate, the border pixel row/column).
  struct Side {
    int axis;
    double at;
    int fixed;
  };
  const Side sides[4] = {
      {0, m.min.x, 0}, {0, m.max.x, g.width - 1}, {1, m.min.y, 0}, {1, m.max.y, g.height - 1}};
  for (const Side& s : sides) {
    const auto span = hull_on_line(hull, s.axis, s.at);
    if (!span) continue;
    const double origin = s.axis == 0 ? g.origin.y : g.origin.x;
    const int count = s.axis == 0 ? g.height : g.width;
    // Pixels whose closed extent meets the crossing interval (floor: a crossing on a pixel
    // border belongs to both pixels, the lower one is covered by the -1 below).
    const int k0 = std::max(0, static_cast<int>(std::floor((span->first - origin) / g.pixel)) - 1);
    const int k1 =
        std::min(count - 1, static_cast<int>(std::floor((span->second - origin) / g.pixel)));
    for (int k = k0; k <= k1; ++k) {
      const int i = s.axis == 0 ? s.fixed : k, j = s.axis == 0 ? k : s.fixed;
      const Box2 pixel{{g.origin.x + i * g.pixel, g.origin.y + j * g.pixel},
                       {g.origin.x + (i + 1) * g.pixel, g.origin.y + (j + 1) * g.pixel}};
      const double top = cell.top + rise * box_reach(pixel, cell.xy);
      if (!(top < static_cast<double>(map.at(i, j)))) return false;
    }
  }
  return true;
}

}  // namespace urbanpvs::preprocess
