// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/CellCullMap.hpp"

#include <algorithm>

#include "urbanpvs/preprocess/CpuRasterizer.hpp"

namespace urbanpvs::preprocess {

void render_sample(const Vec3& sample, std::span<const geometry::Occluder> occluders, CullMap& map,
                   CullMapStats* stats) {
  const Box2 clip = map.grid().bounds().grown(map.grid().pixel);
  for (const geometry::Occluder& o : occluders)
    geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
      const auto shadow = occluder_shadow(sample, a, b, o.top_z, clip);
      if (!shadow) return;
      const std::size_t px = rasterize_max(*shadow, map);
      if (stats) ++stats->shadows, stats->pixels_written += px;
    });
}

CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                      std::span<const geometry::Occluder> occluders, CullMapStats* stats) {
  CullMap cell(grid);
  if (samples.empty()) return cell;
  CullMap one(grid);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    one.fill(CullMap::kNothingHidden);
    render_sample(samples[s], occluders, one, stats);
    if (s == 0) {
      cell.values() = one.values();
    } else {
      std::vector<float>& z = cell.values();
      const std::vector<float>& w = one.values();
      for (std::size_t k = 0; k < z.size(); ++k) z[k] = std::min(z[k], w[k]);
    }
  }
  return cell;
}

}  // namespace urbanpvs::preprocess
