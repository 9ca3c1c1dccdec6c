// SPDX-License-Identifier: GPL-3.0-or-later
// Outlines with fewer walls that never leave the occluder: the far field's occluders (thesis
// 5.6). A sample's horizon pays per wall it adds, and real outlines (3D BAG, OSM, stepped roof
// levels) carry many short walls that, a few hundred metres away, close the same sectors as
// one wall would. Any part of an occluder occludes no more than the whole (thesis 4.2.1: each
// wall a sight line crosses hides only what lies below its shadow plane), so a horizon built
// from a polygon inside the occluder hides a subset of what the occluder hides.
#pragma once

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

/// `polygon` (outer ring counter-clockwise, holes clockwise, every ring simple) with corners
/// cut off while that keeps it inside `polygon`: a vertex goes when it is a convex corner of the
/// solid (or on a straight line), the triangle it cuts off holds no other vertex of any ring,
/// and every input vertex the new chord replaces (this corner and those cut before it there,
/// at most 64) lies within `tolerance` (m) of the chord's line. So the result keeps every ring,
/// each simple with at least three of its input vertices in order, lies inside `polygon`, and no
/// input boundary it cut away is farther than `tolerance` from it. Concave corners are never cut:
/// that would grow the solid.
Polygon simplified_inward(const Polygon& polygon, double tolerance);

}  // namespace urbanpvs::geometry
