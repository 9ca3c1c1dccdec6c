// SPDX-License-Identifier: GPL-3.0-or-later
// Turns raw input rings into valid polygons. What needs no judgement (closing point, repeated
// points, orientation) is fixed and counted; what is broken (self-intersections, bow-ties,
// spikes, zero-area rings, holes that cross or leave their outer ring) is repaired into the
// region the outer ring winds around, less the holes, and every such repair is reported. Only
// non-finite coordinates, and any geometric repair in strict mode, are InputErrors.
#pragma once

#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

struct RingContext {
  std::string file;
  std::string feature;
  /// Count orientation fixes as repairs. Off for rings projected from 3D surfaces, whose 2D
  /// orientation depends on the surface normal and is no defect of the input.
  bool count_orientation = true;
  /// Geometric repairs become InputError(InvalidGeometry) instead (`--strict`).
  bool strict = false;
};

/// Builds valid polygons from `rings` (first the outer ring, then holes; each ring open or
/// closed): one polygon for valid input, the repaired pieces (disjoint, strictly simple, never
/// outside the region the input rings enclose) for broken input, nothing when no area is left.
/// Geometric repairs are appended to report.repairs as "file: feature: what". Throws
/// InputError(InvalidGeometry) for non-finite coordinates, and in strict mode for any defect.
std::vector<Polygon> clean_polygon(std::vector<Ring> rings, const RingContext& ctx,
                                   ReadReport& report);

/// Why `poly` is not a valid simple polygon with holes, or an empty string when it is. Used by
/// clean_polygon and by tests; O(n^2) in the number of edges, which footprints keep small.
std::string polygon_defect(const Polygon& poly);

}  // namespace urbanpvs::geometry
