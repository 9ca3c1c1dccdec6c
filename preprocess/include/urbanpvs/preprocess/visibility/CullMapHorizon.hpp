// SPDX-License-Identifier: GPL-3.0-or-later
// The cull-map horizon (thesis 5.6.1): the heights along the border of a cull map are a
// cross-section through the cell's umbra. Every sight line from the cell to something outside
// the map leaves the map through one border pixel; where it passes below that pixel's height it
// is blocked (the map guarantees that everything below its height is hidden from every viewpoint
// of the cell), and so is everything behind.
#pragma once

#include "urbanpvs/preprocess/visibility/CullMap.hpp"

namespace urbanpvs::preprocess {

/// The view cell as the horizon test sees it: its ground rectangle and the top of its eye band.
struct CellBox {
  Box2 xy;
  double top = 0;
};

/// True when `box` (entirely outside the map: its ground rectangle does not meet the map's
/// interior) is hidden from every viewpoint in `cell` (inside the map) by the horizon of `map`.
/// The view channel between the two boxes (thesis figure 5.6) is bounded on the sides by the
/// convex hull of their ground rectangles and on top by the sight lines from the cell's top to the
/// box's top; the box is hidden when that top bound passes below the height of every border pixel
/// the channel crosses.
bool hidden_behind_horizon(const CullMap& map, const CellBox& cell, const geometry::Box3& box);

}  // namespace urbanpvs::preprocess
