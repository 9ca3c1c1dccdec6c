// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CpuRasterizer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "urbanpvs/preprocess/visibility/AlsoForAvx2.hpp"

namespace urbanpvs::preprocess {

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
  std::size_t written = 0;
  for (int j = j0; j <= j1; ++j) {
    const double y = g.origin.y + (j + 0.5) * g.pixel;
    // A convex polygon meets the row's centre line in one interval [xl, xr).
    double xl = std::numeric_limits<double>::infinity(), xr = -xl;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
      if ((p.y <= y) == (q.y <= y)) continue;  // half-open in y: the edge spans [min, max)
      const double x = p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y);
      xl = std::min(xl, x);
      xr = std::max(xr, x);
    }
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
