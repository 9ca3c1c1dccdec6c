// SPDX-License-Identifier: GPL-3.0-or-later
// The ground outline of a city object: the convex hull of its geometry seen from above. A cull
// map decides an object by the pixels it covers (thesis 4.3.3); its axis-aligned box covers
// twice the area of a rotated building (Delft: hull / box = 0.45 on average, the 3D BAG tile
// 0.67, a generated city 0.81), and the pixels beside the building, in the street, are the
// ones a shadow covers least.
#pragma once

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// Counter-clockwise convex hull (CGAL) of `points`; its vertices are input points, so it
/// contains every one of them exactly. Empty when they span no area (fewer than three, or all
/// on one line).
Ring convex_hull(const std::vector<Vec2>& points);

/// Counter-clockwise convex hull (CGAL) of the xy of every point of `o`'s surfaces, footprints
/// and occluders: it contains every point of the object. When there are no such points, or the
/// box reaches beyond them (geometry the reader kept out of its surfaces), it is the box's
/// rectangle. Empty only when the box is empty.
Ring object_hull(const CityObject& o);

/// The outline a cull map tests `o` over: object_hull(o), but the box's rectangle for an object
/// that does not occlude (it is tested over its whole box: it may be anywhere in it).
Ring object_outline(const CityObject& o);

}  // namespace urbanpvs::geometry
