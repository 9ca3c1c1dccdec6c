// SPDX-License-Identifier: GPL-3.0-or-later
// Exact union of footprints (CGAL Boolean set operations with an exact kernel): buildings that
// share a wall become one polygon without a sliver between them (thesis 5.4: connected buildings
// occlude as one block).
#pragma once

#include <vector>

#include "urbanpvs/geometry/Polygon2.hpp"

namespace urbanpvs::geometry {

/// The union of `polys` as disjoint polygons with holes (outer CCW, holes CW), with collinear
/// and repeated vertices removed. Input polygons must be valid (see polygon_defect).
std::vector<Polygon> union_polygons(const std::vector<Polygon>& polys);

}  // namespace urbanpvs::geometry
