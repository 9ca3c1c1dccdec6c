// SPDX-License-Identifier: GPL-3.0-or-later
// Reading the PVS off a cull map (thesis 4.3.3): an object is hidden when its top lies below the
// umbra over every pixel its outline touches.
#pragma once

#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"

namespace urbanpvs::preprocess {

/// True when `box` is hidden: every pixel its ground rectangle touches (any overlap, the border
/// included, counts) holds a height above box.zmax. A box reaching outside the map is never
/// hidden: nothing is known there.
bool hidden_by(const CullMap& map, const geometry::Box3& box);

/// The pixels [first, last] of row j of `g` that `outline` touches (any overlap, the border
/// included), within `range` (those its box touches); first > last when the outline does not
/// reach the row. An outline of fewer than 3 points stands for the box: the range's whole row.
struct PixelSpan {
  long long first, last;
};
PixelSpan outline_row(const CullMapGrid& g, const geometry::Ring& outline,
                      const CullMapGrid::PixelRange& range, long long j);

/// As hidden_by(map, box), over the pixels `outline` touches instead of the whole rectangle:
/// row by row, from the leftmost to the rightmost point of the outline in that row (a convex
/// outline covers no less; geometry::object_outline). The outline lies within the box; one
/// with fewer than 3 points stands for the box.
bool hidden_by(const CullMap& map, const geometry::Box3& box, const geometry::Ring& outline);

/// Indices of the objects not hidden by `map`, ascending; object i is tested by outlines[i].
std::vector<std::uint32_t> visible_objects(const CullMap& map,
                                           const std::vector<geometry::CityObject>& objects,
                                           const std::vector<geometry::Ring>& outlines);

}  // namespace urbanpvs::preprocess
