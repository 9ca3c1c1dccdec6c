// SPDX-License-Identifier: GPL-3.0-or-later
// The triangles of a face of a solid in 3D: planar only to its coordinates' rounding, perhaps
// with holes. Kept in its own translation unit: it instantiates CGAL's constrained
// triangulation.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "urbanpvs/geometry/city/Vector.hpp"

namespace urbanpvs::geometry {

/// Newell's normal of the ring of `n` corners at(0) .. at(n - 1): its length is twice the
/// ring's area, and it points to where the ring is seen counter-clockwise. Sound for rings that
/// are planar only to their rounding.
template <class At>
Vec3 newell_normal(std::size_t n, At at) {
  Vec3 normal{0, 0, 0};
  for (std::size_t k = 0; k < n; ++k) normal += glm::cross(Vec3(at(k)), Vec3(at((k + 1) % n)));
  return normal;
}

/// Appends the triangles (indices into `points`) covering the face whose outer ring and holes
/// are `rings` (indices into `points`), triangulated in the plane its normal is largest across,
/// with no vertex added. False, and nothing appended, when the rings cross each other or
/// themselves, or the face has no area in that plane.
bool triangulate_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                      std::vector<std::array<int, 3>>& out);

}  // namespace urbanpvs::geometry
