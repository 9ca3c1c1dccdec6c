// SPDX-License-Identifier: GPL-3.0-or-later
#include "RingLocator.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace urbanpvs::geometry::detail {
namespace {

using Point = RingLocator::K::Point_2;

/// p on the closed segment a-b: collinear and within its box (exact: doubles compared as they
/// are, the orientation predicate exact).
bool on_segment(const Point& a, const Point& b, const Point& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y()) &&
         CGAL::orientation(a, b, p) == CGAL::COLLINEAR;
}

}  // namespace

RingLocator::RingLocator(const Ring& ring) {
  points_.reserve(ring.size());
  for (Vec2 v : ring) points_.emplace_back(v.x, v.y);
  const std::size_t n = points_.size();
  if (n < 3) return;
  xmin_ = xmax_ = points_[0].x();
  ymin_ = ymax_ = points_[0].y();
  for (const Point& q : points_) {
    xmin_ = std::min(xmin_, q.x());
    xmax_ = std::max(xmax_, q.x());
    ymin_ = std::min(ymin_, q.y());
    ymax_ = std::max(ymax_, q.y());
  }
  // About two edges a strip for a ring whose edges are short against its height; an edge that
  // spans several strips is filed in each, which the bound on the filed entries caps.
  strips_ = std::clamp<std::size_t>(n / 2, 1, std::size_t{1} << 16);
  // The first and last strip of edge i.
  auto strips_of_edge = [&](std::size_t i) {
    const double y0 = points_[i].y(), y1 = points_[(i + 1) % n].y();
    return std::pair{strip_of(std::min(y0, y1)), strip_of(std::max(y0, y1))};
  };
  for (;;) {
    strip_ = ymax_ > ymin_ ? (ymax_ - ymin_) / static_cast<double>(strips_) : 1.0;
    if (strips_ == 1) break;
    std::size_t entries = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto [s0, s1] = strips_of_edge(i);
      entries += s1 - s0 + 1;
    }
    if (entries <= 8 * n) break;
    strips_ = std::max<std::size_t>(1, strips_ / 4);
  }
  start_.assign(strips_ + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto [s0, s1] = strips_of_edge(i);
    for (std::size_t s = s0; s <= s1; ++s) ++start_[s + 1];
  }
  for (std::size_t s = 0; s < strips_; ++s) start_[s + 1] += start_[s];
  edges_.resize(start_.back());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const auto [s0, s1] = strips_of_edge(i);
    for (std::size_t s = s0; s <= s1; ++s) edges_[fill[s]++] = static_cast<std::uint32_t>(i);
  }
}

std::size_t RingLocator::strip_of(double y) const {
  const double k = std::floor((y - ymin_) / strip_);
  return static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(strips_ - 1)));
}

CGAL::Bounded_side RingLocator::side(const Point& p) const {
  const std::size_t n = points_.size();
  if (n < 3 || !(p.x() >= xmin_ && p.x() <= xmax_ && p.y() >= ymin_ && p.y() <= ymax_))
    return CGAL::ON_UNBOUNDED_SIDE;
  // Every edge whose y-range holds p.y is filed in p's strip (the strips of both ends bracket
  // it: strip_of is monotone).
  const std::size_t s = strip_of(p.y());
  bool inside = false;
  for (std::uint32_t e = start_[s]; e < start_[s + 1]; ++e) {
    const Point& a = points_[edges_[e]];
    const Point& b = points_[(edges_[e] + 1) % n];
    if (on_segment(a, b, p)) return CGAL::ON_BOUNDARY;
    // The ray from p towards +x crosses the edge: its ends on either side of the line y = p.y
    // (an end on the line counts as below it, so a vertex on the ray is crossed once or not at
    // all), and p to the left of the crossing.
    if ((a.y() > p.y()) == (b.y() > p.y())) continue;
    const CGAL::Orientation o = CGAL::orientation(a, b, p);
    if (a.y() < b.y() ? o == CGAL::LEFT_TURN : o == CGAL::RIGHT_TURN) inside = !inside;
  }
  return inside ? CGAL::ON_BOUNDED_SIDE : CGAL::ON_UNBOUNDED_SIDE;
}

PolygonLocator::PolygonLocator(const Polygon& polygon) : outer_(polygon.outer) {
  holes_.reserve(polygon.holes.size());
  for (const Ring& h : polygon.holes) holes_.emplace_back(h);
}

bool PolygonLocator::strictly_inside(const RingLocator::K::Point_2& p) const {
  if (outer_.side(p) != CGAL::ON_BOUNDED_SIDE) return false;
  for (const RingLocator& h : holes_)
    if (h.side(p) != CGAL::ON_UNBOUNDED_SIDE) return false;
  return true;
}

bool PolygonLocator::inside_or_on(const RingLocator::K::Point_2& p) const {
  if (outer_.side(p) == CGAL::ON_UNBOUNDED_SIDE) return false;
  for (const RingLocator& h : holes_)
    if (h.side(p) == CGAL::ON_BOUNDED_SIDE) return false;
  return true;
}

}  // namespace urbanpvs::geometry::detail
