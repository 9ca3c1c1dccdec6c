// SPDX-License-Identifier: GPL-3.0-or-later
// Internal interface of the CGAL translation unit (ViewCellMesh.cpp): the refined constrained
// Delaunay triangulation of free space as plain arrays, so build_view_cells and everything else
// compiles without CGAL's triangulation headers (that TU takes ~12 s and 850 MB at -O2, measured).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::detail {

struct FreeSpaceTriangulation {
  std::vector<Vec2> vertices;                           ///< only those of free triangles
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise
  /// neighbours[t][k]: the free triangle across the edge opposite vertex k, or -1.
  std::vector<std::array<std::int32_t, 3>> neighbours;
  std::size_t constraint_vertices = 0;  ///< CDT vertices before refinement (input + crossings)
  std::size_t sliver_faces = 0;         ///< thin faces along walls left out (see narrow_gap)
  double sliver_area = 0;               ///< their area (m²)
  std::size_t nudged_vertices = 0;      ///< rounded Steiner points moved off an obstacle
  std::size_t unresolved_vertices = 0;  ///< rounded points no nudge could fix (expected: none)
  double seconds_cdt = 0;
  double seconds_refine = 0;
};

/// Triangulates (union of `region`) minus (union of `obstacles`) and refines it with CGAL's
/// Delaunay mesher: no edge longer than `max_edge`, shape bound `shape_bound` (= sin² of the
/// smallest angle the mesher aims at) for triangles whose shortest edge exceeds `min_edge`. Faces
/// of the unrefined triangulation thinner than `narrow_gap` along a wall are left out (0: none).
/// Polygons must have simple rings, in any orientation; they may overlap, touch and cross each
/// other. Every returned vertex lies in the closed free space.
FreeSpaceTriangulation triangulate_free_space(const std::vector<Polygon>& region,
                                              const std::vector<const Polygon*>& obstacles,
                                              double max_edge, double shape_bound, double min_edge,
                                              double narrow_gap);

}  // namespace urbanpvs::geometry::detail
