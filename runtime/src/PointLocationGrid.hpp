// SPDX-License-Identifier: MIT
#pragma once

// The point-location index of the grid section: a uniform grid over the cells' bounding box,
// each grid cell listing (ascending) the view cells whose triangle's bounding box overlaps it.
// Writer and reader map coordinates to grid cells with the same monotonic function, so the
// reader can verify the stored grid is exactly the one the writer builds, and every point inside
// a triangle's box is guaranteed to find the triangle in its grid cell's list.

#include <array>
#include <cstdint>
#include <vector>

#include "HugePages.hpp"
#include "urbanpvs/runtime/Types.hpp"

namespace urbanpvs::runtime::detail {

struct GridGeometry {
  double origin_x = 0;
  double origin_y = 0;
  double size_x = 1;  ///< > 0, finite
  double size_y = 1;  ///< > 0, finite
  std::uint32_t nx = 1;
  std::uint32_t ny = 1;
};

/// Grid column (or row) of coordinate v: floor((v - origin) / size) clamped to [0, n - 1].
/// Monotonic in v (every step rounds monotonically), which is what makes the index exact.
inline std::uint32_t grid_coordinate(double v, double origin, double size,
                                     std::uint32_t n) noexcept {
  const double t = (v - origin) / size;
  if (!(t >= 1.0)) return 0;  // also NaN
  if (t >= static_cast<double>(n)) return n - 1;
  return static_cast<std::uint32_t>(t);
}

/// Inclusive grid range covered by a triangle's bounding box.
struct GridRange {
  std::uint32_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};
GridRange triangle_grid_range(const GridGeometry& grid,
                              const std::array<Point2, 3>& triangle) noexcept;

/// A grid as the writer builds it.
struct BuiltGrid {
  GridGeometry geometry;
  std::vector<std::uint64_t> offsets;  ///< nx * ny + 1 prefix sums into entries
  /// Cell indices, ascending within each grid cell; the reader keeps them (huge pages).
  LargeVector<std::uint32_t> entries;
};

/// Builds the grid for `triangles` with about `grid_cells_per_cell` grid cells per triangle.
BuiltGrid build_grid(const std::vector<std::array<Point2, 3>>& triangles,
                     double grid_cells_per_cell);

}  // namespace urbanpvs::runtime::detail
