// SPDX-License-Identifier: GPL-3.0-or-later
// The triangles of a face of a solid in 3D: planar only to its coordinates' rounding, perhaps
// with holes. Kept in its own translation unit: it instantiates CGAL's constrained
// triangulation.
#pragma once

#include <array>
#include <vector>

#include "urbanpvs/geometry/city/Vector.hpp"

namespace urbanpvs::geometry {

/// Appends the triangles (indices into `points`) covering the face whose outer ring and holes
/// are `rings` (indices into `points`), triangulated in the plane its normal is largest across,
/// with no vertex added. False, and nothing appended, when the rings cross each other or
/// themselves, or the face has no area in that plane.
bool triangulate_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                      std::vector<std::array<int, 3>>& out);

}  // namespace urbanpvs::geometry
