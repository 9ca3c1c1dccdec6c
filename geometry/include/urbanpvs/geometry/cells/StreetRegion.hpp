// SPDX-License-Identifier: GPL-3.0-or-later
// The region of --cells streets: where the input says people can be.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// The street network as disjoint polygons in the local frame: every centre line buffered by
/// half its width, at least 6 m wide in all (segments as rectangles, vertices as octagons, so
/// bends and crossings leave no gaps), with the street areas, fused and simplified within
/// 0.5 m. Lines are first simplified within 0.5 m (OpenStreetMap draws curves with a vertex
/// every metre or two). Narrower strips would only multiply cells.
/// Empty for an empty network.
std::vector<Polygon> street_region(const StreetNetwork& streets);

}  // namespace urbanpvs::geometry
