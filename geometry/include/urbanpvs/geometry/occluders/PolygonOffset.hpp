// SPDX-License-Identifier: GPL-3.0-or-later
// Straight-skeleton offsets (CGAL). The inward offset is the 2D occluder shrinking of thesis
// 7.3.3: every point of the result is at least `d` from the input's boundary (a mitred offset is
// a subset of the exact erosion), so it can stand in for the exact erosion conservatively.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

/// Inward offset of `poly` by `d` > 0. Parts narrower than 2d vanish, so the result may be
/// empty or split into several polygons (holes grow and may merge with the outside).
std::vector<Polygon> shrink_polygon(const Polygon& poly, double d);

/// Outward mitred offset of `poly` by `d` > 0: a superset of the dilation by a disk of radius d.
/// Holes narrower than 2d close. Used to fuse footprints separated by digitizing gaps.
std::vector<Polygon> grow_polygon(const Polygon& poly, double d);

}  // namespace urbanpvs::geometry
