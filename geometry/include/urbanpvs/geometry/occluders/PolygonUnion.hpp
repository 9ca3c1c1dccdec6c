// SPDX-License-Identifier: GPL-3.0-or-later
// Exact union of footprints (CGAL Boolean set operations with an exact kernel): buildings that
// share a wall become one polygon without a sliver between them (thesis 5.4: connected buildings
// occlude as one block).
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

/// The union of `polys` as disjoint, strictly simple polygons with holes (outer CCW, holes CW),
/// collinear vertices removed. Where the exact union only touches itself at a point, that point
/// is pulled 1 µm into the region, so the result is a subset of the exact union (never larger).
/// Input polygons must be valid (see polygon_defect).
std::vector<Polygon> union_polygons(const std::vector<Polygon>& polys);

}  // namespace urbanpvs::geometry
