// SPDX-License-Identifier: MIT
#include "PointLocationGrid.hpp"

#include <algorithm>
#include <cmath>

namespace urbanpvs::runtime::detail {
namespace {

/// Cap on grid cells so the offsets table stays proportional to the file (and below 2^32).
constexpr double kMaxGridCells = 1 << 26;

struct Box {
  double min_x, min_y, max_x, max_y;
};

Box triangle_box(const std::array<Point2, 3>& t) noexcept {
  return {std::min({t[0].x, t[1].x, t[2].x}), std::min({t[0].y, t[1].y, t[2].y}),
          std::max({t[0].x, t[1].x, t[2].x}), std::max({t[0].y, t[1].y, t[2].y})};
}

/// Number of grid cells along an extent, and their size; one cell of size 1 when the extent is
/// empty or not representable.
void size_axis(double extent, double cell, std::uint32_t& n, double& size) {
  const double count = std::ceil(extent / cell);
  if (!(extent > 0) || !std::isfinite(count) || count < 1) {
    n = 1;
    size = 1;
    return;
  }
  n = static_cast<std::uint32_t>(std::min(count, kMaxGridCells));
  size = extent / n;
  if (!(size > 0) || !std::isfinite(size)) {
    n = 1;
    size = 1;
  }
}

GridGeometry make_geometry(const Box& all, double cell) {
  GridGeometry g;
  g.origin_x = all.min_x;
  g.origin_y = all.min_y;
  size_axis(all.max_x - all.min_x, cell, g.nx, g.size_x);
  size_axis(all.max_y - all.min_y, cell, g.ny, g.size_y);
  return g;
}

std::uint64_t range_cells(const GridRange& r) noexcept {
  return std::uint64_t{r.x1 - r.x0 + 1} * (r.y1 - r.y0 + 1);
}

}  // namespace

GridRange triangle_grid_range(const GridGeometry& g, const std::array<Point2, 3>& t) noexcept {
  const Box b = triangle_box(t);
  return {grid_coordinate(b.min_x, g.origin_x, g.size_x, g.nx),
          grid_coordinate(b.max_x, g.origin_x, g.size_x, g.nx),
          grid_coordinate(b.min_y, g.origin_y, g.size_y, g.ny),
          grid_coordinate(b.max_y, g.origin_y, g.size_y, g.ny)};
}

BuiltGrid build_grid(const std::vector<std::array<Point2, 3>>& triangles,
                     double grid_cells_per_cell) {
  BuiltGrid grid;
  GridGeometry& g = grid.geometry;
  std::vector<GridRange> ranges(triangles.size());
  if (!triangles.empty()) {
    Box all = triangle_box(triangles.front());
    for (const auto& t : triangles) {
      const Box b = triangle_box(t);
      all = {std::min(all.min_x, b.min_x), std::min(all.min_y, b.min_y),
             std::max(all.max_x, b.max_x), std::max(all.max_y, b.max_y)};
    }
    const double w = all.max_x - all.min_x;
    const double h = all.max_y - all.min_y;
    const double n = static_cast<double>(triangles.size());
    const double target =
        std::clamp(n * (grid_cells_per_cell > 0 ? grid_cells_per_cell : 1.0), 1.0, kMaxGridCells);
    // Square grid cells of area w*h/target; a degenerate extent gets a single row or column.
    double cell = 1;
    if (w > 0 && h > 0) {
      cell = std::sqrt(w / target * h);
    } else if (w > 0 || h > 0) {
      cell = std::max(w, h) / target;
    }
    // Coarsen while the grid is too large: extreme aspect ratios, or large overlapping
    // triangles that would be listed in very many grid cells each.
    const double max_entries = std::max(64.0 * n, double{1 << 20});
    for (;;) {
      g = make_geometry(all, cell);
      double entries = 0;
      for (std::size_t i = 0; i < triangles.size(); ++i) {
        ranges[i] = triangle_grid_range(g, triangles[i]);
        entries += static_cast<double>(range_cells(ranges[i]));
      }
      if ((static_cast<double>(g.nx) * g.ny <= kMaxGridCells && entries <= max_entries) ||
          (g.nx == 1 && g.ny == 1)) {
        break;
      }
      cell *= 2;
    }
  }
  const std::size_t cells = std::size_t{g.nx} * g.ny;
  // Counting sort: count per grid cell, prefix sums, fill in triangle order (so ascending).
  grid.offsets.assign(cells + 1, 0);
  for (const GridRange& r : ranges) {
    for (std::uint32_t y = r.y0; y <= r.y1; ++y) {
      for (std::uint32_t x = r.x0; x <= r.x1; ++x) ++grid.offsets[y * std::size_t{g.nx} + x + 1];
    }
  }
  for (std::size_t c = 0; c < cells; ++c) grid.offsets[c + 1] += grid.offsets[c];
  grid.entries.resize(grid.offsets[cells]);
  std::vector<std::uint64_t> fill(grid.offsets.begin(), grid.offsets.end() - 1);
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const GridRange& r = ranges[i];
    for (std::uint32_t y = r.y0; y <= r.y1; ++y) {
      for (std::uint32_t x = r.x0; x <= r.x1; ++x) {
        grid.entries[fill[y * std::size_t{g.nx} + x]++] = static_cast<std::uint32_t>(i);
      }
    }
  }
  return grid;
}

}  // namespace urbanpvs::runtime::detail
