// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"

namespace urbanpvs::geometry {

std::vector<Occluder> shrink_blocks(const std::vector<Block>& blocks, double epsilon) {
  std::vector<Occluder> out;
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (const BlockLevel& level : blocks[b].levels)
      for (const Polygon& region : level.region)
        for (Polygon& shape : shrink_polygon(region, epsilon + level.grown_by)) {
          const Box2 box = bounds(shape);
          out.push_back({static_cast<std::uint32_t>(b), level.top_z, std::move(shape), box});
        }
  return out;
}

}  // namespace urbanpvs::geometry
