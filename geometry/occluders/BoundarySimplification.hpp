// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: topology-preserving simplification of polygon boundaries within a tolerance. The
// blocks use it to drop the near-collinear vertices that fused walls leave (a shared wall that
// is not bit-identical in the data); the view cells use it for free space's outline.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::detail {

/// The polygons with every ring simplified together: vertices are removed while every removed
/// point stays within `tolerance` of the new ring, and no two rings come to cross. So every point
/// of an input boundary is within `tolerance` of an output boundary and back, and whatever the
/// output gained lies within `tolerance` of its boundary: eroding the output by r + tolerance
/// stays inside the input eroded by r. A polygon whose simplification would not be a valid
/// polygon is returned as it was.
std::vector<Polygon> simplify_boundaries(const std::vector<Polygon>& polys, double tolerance);

}  // namespace urbanpvs::geometry::detail
