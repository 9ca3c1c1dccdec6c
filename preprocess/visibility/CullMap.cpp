// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CullMap.hpp"

#include <algorithm>
#include <cstdio>

namespace urbanpvs::preprocess {

void CullMapSettings::validate() const {
  if (!(epsilon > 0)) throw std::invalid_argument("epsilon must be > 0 m");
  if (!(pixel > 0)) throw std::invalid_argument("pixel size must be > 0 m");
  if (pixel > max_pixel(epsilon) * (1 + 1e-12)) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "pixel size %.4g m is too large for epsilon %.4g m (needs epsilon >= pixel * "
                  "(sqrt(2)/2 + 1/128), thesis 7.2): lower the pixel size to <= %.4g m or raise "
                  "epsilon to >= %.4g m",
                  pixel, epsilon, max_pixel(epsilon), pixel * (std::sqrt(2.0) / 2 + 1.0 / 128));
    throw std::invalid_argument(msg);
  }
}

CullMapGrid CullMapGrid::covering(const Box2& area, double pixel) {
  CullMapGrid g;
  g.pixel = pixel;
  g.origin = {std::floor(area.min.x / pixel) * pixel, std::floor(area.min.y / pixel) * pixel};
  g.width = std::max(1, static_cast<int>(std::ceil((area.max.x - g.origin.x) / pixel)));
  g.height = std::max(1, static_cast<int>(std::ceil((area.max.y - g.origin.y) / pixel)));
  return g;
}

CullMap::CullMap(const CullMapGrid& grid)
    : grid_(grid),
      z_(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height),
         kNothingHidden) {}

void CullMap::fill(float value) {
  std::fill(z_.begin(), z_.end(), value);
}

bool outside_map(const CullMapGrid& grid, const Box2& box) {
  const Box2 m = grid.bounds();
  return box.max.x <= m.min.x || box.min.x >= m.max.x || box.max.y <= m.min.y ||
         box.min.y >= m.max.y;
}

bool inside_map(const CullMapGrid& grid, const Box2& box) {
  const Box2 m = grid.bounds();
  return box.min.x >= m.min.x && box.max.x <= m.max.x && box.min.y >= m.min.y &&
         box.max.y <= m.max.y;
}

}  // namespace urbanpvs::preprocess
