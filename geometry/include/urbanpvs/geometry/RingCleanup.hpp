// SPDX-License-Identifier: GPL-3.0-or-later
// Turns raw input rings into valid polygons: repairs what can be repaired without guessing
// (closing point, repeated points, orientation) and rejects what cannot (self-intersection,
// zero area, too few points, non-finite coordinates) with an InputError naming the feature.
#pragma once

#include <string>
#include <vector>

#include "urbanpvs/geometry/CityModel.hpp"

namespace urbanpvs::geometry {

struct RingContext {
  std::string file;
  std::string feature;
  /// Count orientation fixes as repairs. Off for rings projected from 3D surfaces, whose 2D
  /// orientation depends on the surface normal and is no defect of the input.
  bool count_orientation = true;
};

/// Builds a polygon from `rings` (first the outer ring, then holes; each ring open or closed).
/// Throws InputError(InvalidGeometry) when a ring cannot be repaired.
Polygon clean_polygon(std::vector<Ring> rings, const RingContext& ctx, ReadReport& report);

/// Why `poly` is not a valid simple polygon with holes, or an empty string when it is. Used by
/// clean_polygon and by tests; O(n^2) in the number of edges, which footprints keep small.
std::string polygon_defect(const Polygon& poly);

}  // namespace urbanpvs::geometry
