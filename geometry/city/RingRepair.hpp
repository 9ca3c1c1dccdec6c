// SPDX-License-Identifier: GPL-3.0-or-later
// Internal interface of the CGAL translation unit RingRepair.cpp.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::detail {

/// The region where rings[0] winds non-zero and the other rings (holes), each turned to run
/// counter-clockwise by its signed area, wind zero together, as disjoint,
/// strictly simple polygons (outer CCW, holes CW). Rings may intersect themselves and each
/// other, fold back (spikes) and repeat points; zero-area pieces vanish. Empty when nothing of
/// positive area is left.
std::vector<Polygon> fill_by_winding(const std::vector<Ring>& rings);

}  // namespace urbanpvs::geometry::detail
