// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CpuRasterizer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "urbanpvs/preprocess/visibility/AlsoForAvx2.hpp"

namespace urbanpvs::preprocess {

namespace {

// The rows of [j0, j1] whose centre line y meets the edge p -> q under the half-open rule
// (min(p.y, q.y) <= y < max(p.y, q.y)), as [*ja, *jb]; the row's y rises with j, so they are
// a run. The estimate from a division is checked and moved with the exact test.
void rows_of_edge(const CullMapGrid& g, double lo, double hi, int j0, int j1, int* ja, int* jb) {
  auto row_y = [&](int j) { return g.origin.y + (j + 0.5) * g.pixel; };
  auto estimate = [&](double y) {
    const double r = std::ceil((y - g.origin.y) / g.pixel - 0.5);
    return static_cast<int>(std::clamp(r, static_cast<double>(j0), static_cast<double>(j1) + 1));
  };
  int a = estimate(lo);  // the first row with y >= lo
  while (a > j0 && row_y(a - 1) >= lo) --a;
  while (a <= j1 && row_y(a) < lo) ++a;
  int b = estimate(hi);  // the first row with y >= hi
  while (b > j0 && row_y(b - 1) >= hi) --b;
  while (b <= j1 && row_y(b) < hi) ++b;
  *ja = a;
  *jb = b - 1;
}

}  // namespace

// Two builds of the same code (AlsoForAvx2.hpp): the row loop below is most of a bake's map
// time, and AVX2 doubles its width; both give bit-identical maps.
URBANPVS_ALSO_FOR_AVX2 std::size_t rasterize_max(const OccluderShadow& shadow, CullMap& map) {
  const CullMapGrid& g = map.grid();
  const ShadowPolygon& poly = shadow.polygon;
  double ymin = poly[0].y, ymax = poly[0].y;
  for (Vec2 p : poly) ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
  // Rows whose centre line lies in [ymin, ymax).
  const int j0 = std::max(0, static_cast<int>(std::ceil((ymin - g.origin.y) / g.pixel - 0.5)));
  const int j1 =
      std::min(g.height - 1, static_cast<int>(std::ceil((ymax - g.origin.y) / g.pixel - 0.5)) - 1);
  if (j1 < j0) return 0;
  // A convex polygon meets each row's centre line in one interval [xl, xr): found edge by edge
  // over the rows each edge spans, not by testing every edge in every row (that scan was a third
  // of the rasterizer's time). Same arithmetic per row and edge, in the same edge order: the
  // same intervals.
  thread_local std::vector<double> left, right;
  const auto rows = static_cast<std::size_t>(j1 - j0 + 1);
  left.assign(rows, std::numeric_limits<double>::infinity());
  right.assign(rows, -std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
    if (!(p.y != q.y)) continue;  // a horizontal edge spans no row's centre line
    int ja = 0, jb = -1;
    rows_of_edge(g, std::min(p.y, q.y), std::max(p.y, q.y), j0, j1, &ja, &jb);
    for (int j = ja; j <= jb; ++j) {
      const double y = g.origin.y + (j + 0.5) * g.pixel;
      const double x = p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y);
      const auto r = static_cast<std::size_t>(j - j0);
      left[r] = std::min(left[r], x);
      right[r] = std::max(right[r], x);
    }
  }
  std::size_t written = 0;
  for (int j = j0; j <= j1; ++j) {
    const double y = g.origin.y + (j + 0.5) * g.pixel;
    const double xl = left[static_cast<std::size_t>(j - j0)];
    const double xr = right[static_cast<std::size_t>(j - j0)];
    if (!(xl < xr)) continue;
    const int i0 = std::max(0, static_cast<int>(std::ceil((xl - g.origin.x) / g.pixel - 0.5)));
    const int i1 =
        std::min(g.width - 1, static_cast<int>(std::ceil((xr - g.origin.x) / g.pixel - 0.5)) - 1);
    // Along the row the height is linear: z(i) = row + i·step, exactly as height(center(i, j)).
    const double row = shadow.height({g.origin.x + 0.5 * g.pixel, y});
    const double step = shadow.a * g.pixel;
    float* cells = &map.at(0, j);
    // float_below without branches, so the loop vectorizes: one float step down (in the bit
    // pattern: towards zero for negatives, away from it for positives, +0 taken as -0) where the
    // rounded value came out above the exact one.
    for (int i = i0; i <= i1; ++i) {
      const double exact = row + i * step;
      float f = static_cast<float>(exact);
      const bool high = static_cast<double>(f) > exact;
      f = f == 0.0f ? -0.0f : f;
      std::int32_t bits = std::bit_cast<std::int32_t>(f);
      bits += high ? (bits < 0 ? 1 : -1) : 0;
      f = std::bit_cast<float>(bits);
      cells[i] = cells[i] < f ? f : cells[i];
    }
    if (i1 >= i0) written += static_cast<std::size_t>(i1 - i0 + 1);
  }
  return written;
}

}  // namespace urbanpvs::preprocess
