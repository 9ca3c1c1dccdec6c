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

/// A 2.5D occluder: the prism over `shape` from the ground up to `top_z`; its edges cast the
/// occluder shadows of thesis 4.2.1.
struct Occluder {
  std::uint32_t block = 0;  ///< index into the blocks it was shrunk from
  double top_z = 0;
  Polygon shape;
  Box2 bounds;
};

/// Erodes every level of every block by `epsilon` (m, > 0) with the straight-skeleton inward
/// offset (a subset of the exact erosion). Pieces that vanish are dropped, splits kept apart.
std::vector<Occluder> shrink_blocks(const std::vector<Block>& blocks, double epsilon);

}  // namespace urbanpvs::geometry
