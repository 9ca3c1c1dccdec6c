// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace urbanpvs::preprocess {
namespace {

/// Widening of every row and column range of an outline, in metres: the rounding of an
/// interpolated crossing (coordinates of a few km carry errors near 1e-12 m) must never move a
/// touched pixel out of the range.
constexpr double kRowSlack = 1e-7;

/// The x extent of `outline` within the horizontal strip [y0, y1]: every point of the polygon
/// in the strip lies between two of its boundary points in the strip, so the boundary's extent
/// is the polygon's. Empty (lo > hi) when the outline does not reach the strip.
std::pair<double, double> extent_in_strip(const geometry::Ring& outline, double y0, double y1) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t e = 0; e < outline.size(); ++e) {
    const Vec2 p = outline[e], q = outline[(e + 1) % outline.size()];
    const double a = std::max(std::min(p.y, q.y), y0), b = std::min(std::max(p.y, q.y), y1);
    if (a > b) continue;
    const double left = std::min(p.x, q.x), right = std::max(p.x, q.x);
    if (p.y == q.y) {
      lo = std::min(lo, left);
      hi = std::max(hi, right);
      continue;
    }
    for (const double y : {a, b}) {
      // Clamped into the edge's own x range, whatever the division rounds to.
      const double x = std::clamp(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y), left, right);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  return {lo, hi};
}

}  // namespace

bool hidden_by(const CullMap& map, const geometry::Box3& box) {
  return hidden_by(map, box, geometry::Ring{});  // no outline: the box's whole rectangle
}

PixelSpan outline_row(const CullMapGrid& g, const geometry::Ring& outline,
                      const CullMapGrid::PixelRange& range, long long j) {
  if (outline.size() < 3) return {range.i0, range.i1};
  const double k = g.pixel;
  const double y0 = g.origin.y + static_cast<double>(j) * k;
  const auto [lo, hi] = extent_in_strip(outline, y0 - kRowSlack, y0 + k + kRowSlack);
  if (lo > hi) return {1, 0};  // no point of the object in this row
  return {
      std::max(range.i0, static_cast<long long>(std::floor((lo - kRowSlack - g.origin.x) / k))),
      std::min(range.i1, static_cast<long long>(std::floor((hi + kRowSlack - g.origin.x) / k)))};
}

bool hidden_by(const CullMap& map, const geometry::Box3& box, const geometry::Ring& outline) {
  const CullMapGrid& g = map.grid();
  if (box.xy.empty()) return false;
  const CullMapGrid::PixelRange r = g.touched(box.xy);
  if (r.i0 < 0 || r.j0 < 0 || r.i1 >= g.width || r.j1 >= g.height) return false;
  for (long long j = r.j0; j <= r.j1; ++j) {
    const PixelSpan row = outline_row(g, outline, r, j);
    for (long long i = row.first; i <= row.last; ++i)
      if (!(box.zmax < static_cast<double>(map.at(static_cast<int>(i), static_cast<int>(j)))))
        return false;
  }
  return true;
}

std::vector<std::uint32_t> visible_objects(const CullMap& map,
                                           const std::vector<geometry::CityObject>& objects,
                                           const std::vector<geometry::Ring>& outlines) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (!hidden_by(map, objects[i].bbox, outlines[i])) out.push_back(objects[i].index);
  return out;
}

}  // namespace urbanpvs::preprocess
