// SPDX-License-Identifier: GPL-3.0-or-later
// Internal interface of the CGAL translation unit BoundarySimplification.cpp.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::detail {

/// The polygons with every ring simplified together (CGAL's topology-preserving polyline
/// simplification): vertices are removed while every removed point stays within `tolerance` of
/// the new ring, and no two rings come to cross. So every point of an input boundary is within
/// `tolerance` of an output boundary and back. A polygon whose simplification would not be a
/// valid polygon is returned as it was.
std::vector<Polygon> simplify_boundaries(const std::vector<Polygon>& polys, double tolerance);

}  // namespace urbanpvs::geometry::detail
