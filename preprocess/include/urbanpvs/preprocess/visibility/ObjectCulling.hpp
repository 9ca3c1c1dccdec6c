// SPDX-License-Identifier: GPL-3.0-or-later
// Reading the PVS off a cull map (thesis 4.3.3): an object is hidden when its top lies below the
// umbra over every pixel its footprint touches.
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

/// Indices of the objects not hidden by `map`, ascending.
std::vector<std::uint32_t> visible_objects(const CullMap& map,
                                           const std::vector<geometry::CityObject>& objects);

}  // namespace urbanpvs::preprocess
