// SPDX-License-Identifier: GPL-3.0-or-later
// Shrunk occluders (thesis 5.2.1, 7.2, 7.3.3): each block level eroded by ε in 2D. An object
// hidden by the shrunk occluders from a sample point stays hidden from every viewpoint within ε
// of it, and with ε >= k·√2/2 rasterizing their shadows into a cull map of pixel size k is
// conservative too. Eroding in the plane only is enough because samples sit on the top face of a
// view cell (thesis 7.4: the cylinder neighbourhood of 2.5D scenes).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/occluders/Blocks.hpp"

namespace urbanpvs::geometry {

/// A 2.5D occluder: the prism over `shape` from the ground up to its top, a plane: flat at
/// `top_z` for the blocks' levels, sloped under a roof face (RoofPlaneOccluders.hpp). Its edges
/// cast the occluder shadows of thesis 4.2.1; an edge whose ends lie at different heights casts
/// the shadow of the plane through the sample and the sloped edge.
struct Occluder {
  std::uint32_t block = 0;  ///< index into the blocks it was shrunk from
  double top_z = 0;         ///< the top's height at `origin` (everywhere when flat)
  Polygon shape;
  Box2 bounds;
  Vec2 slope{0, 0};  ///< the top's gradient: 0 for a flat top
  Vec2 origin{0, 0};

  bool sloped() const { return slope.x != 0 || slope.y != 0; }
  /// The top's height over `p`: exactly top_z when flat.
  double top_at(Vec2 p) const {
    return sloped() ? top_z + slope.x * (p.x - origin.x) + slope.y * (p.y - origin.y) : top_z;
  }
  /// Bounds of the top over the shape, from its bounding box's corners (a plane's extremes over
  /// a box lie at corners): at least its highest point, at most its lowest.
  double top_high() const { return sloped() ? top_at(corner_towards(slope)) : top_z; }
  double top_low() const { return sloped() ? top_at(corner_towards(-slope)) : top_z; }

 private:
  Vec2 corner_towards(Vec2 d) const {
    return {d.x >= 0 ? bounds.max.x : bounds.min.x, d.y >= 0 ? bounds.max.y : bounds.min.y};
  }
};

/// Erodes every level of every block by `epsilon` (m, > 0) with the straight-skeleton inward
/// offset (a subset of the exact erosion). Pieces that vanish are dropped, splits kept apart.
std::vector<Occluder> shrink_blocks(const std::vector<Block>& blocks, double epsilon);

}  // namespace urbanpvs::geometry
