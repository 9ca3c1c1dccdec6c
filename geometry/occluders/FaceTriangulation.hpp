// SPDX-License-Identifier: GPL-3.0-or-later
// The triangles of a face of a solid in 3D: planar only to its coordinates' rounding, perhaps
// with holes. Kept in its own translation unit: it instantiates CGAL's constrained
// triangulation.
#pragma once

#include <array>
#include <cstddef>
#include <utility>
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

/// The axis a face is triangulated across: the one its normal `n` is largest along (0 x, 1 y,
/// 2 z).
inline int dominant_axis(const Vec3& n) {
  const Vec3 a = glm::abs(n);
  return a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
}

/// `p` in the plane across axis `drop`, as a cyclic turn of its coordinates: (y, z), (z, x) or
/// (x, y). A ring counter-clockwise there is counter-clockwise seen from the axis's positive end.
inline Vec2 planar(const Vec3& p, int drop) {
  return drop == 0 ? Vec2{p.y, p.z} : drop == 1 ? Vec2{p.z, p.x} : Vec2{p.x, p.y};
}

/// Appends the triangles (indices into `points`) covering the face whose outer ring and holes
/// are `rings` (indices into `points`), triangulated in the plane its normal is largest across,
/// with no vertex added. False, and nothing appended, when the rings cross each other or
/// themselves, or the face has no area in that plane.
bool triangulate_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                      std::vector<std::array<int, 3>>& out);

/// As triangulate_face, with the segments `cuts` (pairs of indices into `points`, lying in the
/// face) as edges of the triangles too: the face cut along them. False, and nothing appended,
/// also when a cut crosses a ring or another cut, or one of its ends lies on a ring's edge or
/// on one point of the plane with a corner of another index.
bool triangulate_face(const std::vector<Vec3>& points, const std::vector<std::vector<int>>& rings,
                      const std::vector<std::pair<int, int>>& cuts,
                      std::vector<std::array<int, 3>>& out);

}  // namespace urbanpvs::geometry
