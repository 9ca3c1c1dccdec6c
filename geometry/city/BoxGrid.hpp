// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: a uniform grid of buckets over a set of boxes, each bucket listing (in ascending
// order) the items whose box overlaps it. View cells, terrain triangles and footprints are spread
// evenly over a city, so a uniform grid answers "what is near p" in O(1) without a tree.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::detail {

class BoxGrid {
 public:
  BoxGrid() = default;

  /// Buckets are squares sized for about `per_bucket` items each (at least 1e-3 m, at most
  /// 4096 buckets a side, so memory stays linear in the number of items).
  explicit BoxGrid(const std::vector<Box2>& boxes, double per_bucket = 2.0) {
    for (const Box2& b : boxes) extent_.extend(b);
    if (extent_.empty()) return;
    const double w = extent_.max.x - extent_.min.x, h = extent_.max.y - extent_.min.y;
    double size = std::sqrt(std::max(w * h, 1e-6) * per_bucket / double(boxes.size()));
    size = std::max({size, w / 4096.0, h / 4096.0, 1e-3});
    size_ = size;
    nx_ = static_cast<std::int64_t>(w / size) + 1;
    ny_ = static_cast<std::int64_t>(h / size) + 1;
    std::vector<std::uint32_t> count(static_cast<std::size_t>(nx_ * ny_) + 1, 0);
    auto for_buckets = [&](const Box2& b, auto&& f) {
      if (b.empty()) return;
      const std::int64_t x0 = clamp_x(b.min.x), x1 = clamp_x(b.max.x);
      const std::int64_t y0 = clamp_y(b.min.y), y1 = clamp_y(b.max.y);
      for (std::int64_t y = y0; y <= y1; ++y)
        for (std::int64_t x = x0; x <= x1; ++x) f(static_cast<std::size_t>(y * nx_ + x));
    };
    for (const Box2& b : boxes) for_buckets(b, [&](std::size_t k) { ++count[k + 1]; });
    for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
    start_ = count;
    items_.resize(count.back());
    for (std::size_t i = 0; i < boxes.size(); ++i)
      for_buckets(boxes[i], [&](std::size_t k) { items_[count[k]++] = std::uint32_t(i); });
  }

  bool empty() const { return items_.empty(); }
  const Box2& extent() const { return extent_; }
  double bucket_size() const { return size_; }
  std::int64_t columns() const { return nx_; }
  std::int64_t rows() const { return ny_; }

  /// The items whose box overlaps the bucket holding p; empty outside the grid's extent.
  std::span<const std::uint32_t> at(Vec2 p) const {
    if (items_.empty() || !(p.x >= extent_.min.x && p.x <= extent_.max.x && p.y >= extent_.min.y &&
                            p.y <= extent_.max.y))
      return {};
    return bucket(clamp_x(p.x), clamp_y(p.y));
  }

  /// The items of bucket (x, y); empty for buckets outside the grid.
  std::span<const std::uint32_t> bucket(std::int64_t x, std::int64_t y) const {
    if (x < 0 || y < 0 || x >= nx_ || y >= ny_) return {};
    const auto k = static_cast<std::size_t>(y * nx_ + x);
    return {items_.data() + start_[k], items_.data() + start_[k + 1]};
  }

  /// Bucket column / row of a coordinate, clamped into the grid.
  std::int64_t clamp_x(double x) const { return index(x - extent_.min.x, nx_); }
  std::int64_t clamp_y(double y) const { return index(y - extent_.min.y, ny_); }

  /// Calls f(item) for every item in the square ring of buckets at Chebyshev distance `r` from
  /// bucket (cx, cy); an item may be reported by several buckets.
  template <class F>
  void for_ring(std::int64_t cx, std::int64_t cy, std::int64_t r, F&& f) const {
    auto visit = [&](std::int64_t x, std::int64_t y) {
      for (std::uint32_t i : bucket(x, y)) f(i);
    };
    if (r == 0) return visit(cx, cy);
    for (std::int64_t x = cx - r; x <= cx + r; ++x) visit(x, cy - r), visit(x, cy + r);
    for (std::int64_t y = cy - r + 1; y <= cy + r - 1; ++y) visit(cx - r, y), visit(cx + r, y);
  }

  /// A lower bound on the distance from p to any item not reported by rings 0..r around bucket
  /// (cx, cy) (p's clamped bucket); infinity once the rings cover the whole grid. Only sides with
  /// buckets beyond them count, so the bound also holds for p outside the grid.
  double ring_clearance(Vec2 p, std::int64_t cx, std::int64_t cy, std::int64_t r) const {
    double d = std::numeric_limits<double>::infinity();
    const double x0 = extent_.min.x + double(cx - r) * size_, x1 = x0 + double(2 * r + 1) * size_;
    const double y0 = extent_.min.y + double(cy - r) * size_, y1 = y0 + double(2 * r + 1) * size_;
    if (cx - r > 0) d = std::min(d, p.x - x0);
    if (cx + r < nx_ - 1) d = std::min(d, x1 - p.x);
    if (cy - r > 0) d = std::min(d, p.y - y0);
    if (cy + r < ny_ - 1) d = std::min(d, y1 - p.y);
    return std::max(0.0, d);
  }

 private:
  std::int64_t index(double d, std::int64_t n) const {
    const double k = std::floor(d / size_);
    if (!(k >= 0)) return 0;
    return std::min(static_cast<std::int64_t>(std::min(k, 1e15)), n - 1);
  }

  Box2 extent_;
  double size_ = 1;
  std::int64_t nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> items_;
};

}  // namespace urbanpvs::geometry::detail
