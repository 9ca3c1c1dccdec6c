// SPDX-License-Identifier: GPL-3.0-or-later
// The one 2D and the one 3D vector type of every stage (city model, occluders, cells, cull maps,
// validator): GLM's. Points and directions alike are metres in the city's local frame. The
// runtime keeps types of its own, since it must build with nothing but a C++17 library.
#pragma once

// Vectors are zero when default-constructed, like the plain structs they replaced, and carry
// x/y/z only (no rgba/stpq aliases). Both are set for every user by the urbanpvs_geometry
// target (see geometry/CMakeLists.txt); a translation unit that got GLM another way must not
// silently see uninitialized vectors.
#if !defined(GLM_FORCE_CTOR_INIT) || !defined(GLM_FORCE_XYZW_ONLY)
#error "urbanpvs expects GLM_FORCE_CTOR_INIT and GLM_FORCE_XYZW_ONLY (set by urbanpvs_geometry)"
#endif

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <tuple>

namespace urbanpvs::geometry {

using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;
using glm::dot;

/// The z of the 3D cross product of a and b: > 0 when b turns counter-clockwise from a.
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}

/// x first, then y, then z: GLM has no order of its own, and sorted vertices need one.
inline bool lexicographic_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}

}  // namespace urbanpvs::geometry
