// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/CpuRasterizer.hpp"

#include <algorithm>
#include <cmath>

namespace urbanpvs::preprocess {

std::size_t rasterize_max(const OccluderShadow& shadow, CullMap& map) {
  const CullMapGrid& g = map.grid();
  const std::vector<Vec2>& poly = shadow.polygon;
  double ymin = poly[0].y, ymax = poly[0].y;
  for (Vec2 p : poly) ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
  // Rows whose centre line lies in [ymin, ymax).
  const int j0 = std::max(0, static_cast<int>(std::ceil((ymin - g.origin.y) / g.pixel - 0.5)));
  const int j1 = std::min(g.height - 1, static_cast<int>(std::ceil((ymax - g.origin.y) / g.pixel - 0.5)) - 1);
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
    const int i1 = std::min(g.width - 1, static_cast<int>(std::ceil((xr - g.origin.x) / g.pixel - 0.5)) - 1);
    for (int i = i0; i <= i1; ++i) {
      const float z = float_below(shadow.height(g.center(i, j)));
      float& cell = map.at(i, j);
      if (z > cell) cell = z;
    }
    if (i1 >= i0) written += static_cast<std::size_t>(i1 - i0 + 1);
  }
  return written;
}

}  // namespace urbanpvs::preprocess
