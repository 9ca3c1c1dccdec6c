// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Plain value types shared by the writer (PvsBake) and the reader (PvsFile).

#include <array>
#include <cstdint>

namespace urbanpvs::runtime {

/// "No cell": locate() result for points outside every cell, and an absent neighbour.
inline constexpr std::uint32_t kNoCell = 0xFFFFFFFFu;

/// A 2D point in the stored local frame (metres).
struct Point2 {
  double x = 0;
  double y = 0;
};

/// Axis-aligned box in the stored local frame: min x, min y, min z, max x, max y, max z (metres).
using Bbox = std::array<double, 6>;

/// Geodetic origin of the local east-north-up frame (only meaningful for geographic inputs).
struct GeodeticOrigin {
  double lat_deg = 0;  ///< WGS84 latitude, degrees, [-90, 90]
  double lon_deg = 0;  ///< WGS84 longitude, degrees
  double h_m = 0;      ///< WGS84 ellipsoidal height, metres
};

/// How the offline bake was configured; stored so a file says how it was made.
struct BakeSettings {
  double epsilon_m = 0;          ///< occluder shrinking epsilon (m)
  double pixel_size_m = 0;       ///< cull-map pixel size (m)
  double max_cell_edge_m = 0;    ///< longest view-cell edge (m)
  double eye_min_m = 0;          ///< lowest eye height above ground (m)
  double eye_max_m = 0;          ///< highest eye height above ground (m)
  std::uint64_t input_hash = 0;  ///< 64-bit hash of the input city (writer's choice of hash)
};

/// A view cell: a vertical triangular prism. Neighbour i is across the edge from vertex i to
/// vertex (i + 1) % 3, or kNoCell.
struct CellGeometry {
  std::array<Point2, 3> triangle{};
  double z_min = 0;  ///< bottom of the prism (m, local frame)
  double z_max = 0;  ///< top of the prism (m, local frame)
  std::array<std::uint32_t, 3> neighbours{kNoCell, kNoCell, kNoCell};
};

/// True when (x, y) lies in the closed triangle. Shared edges are decided the same way for both
/// triangles (each edge is evaluated in a canonical vertex order), so a point on a shared edge is
/// in at least one of the two and the test never leaves gaps between neighbours; degenerate
/// (zero-area) triangles contain nothing. Points outside the triangle's bounding box are always
/// outside. This is the predicate PvsFile::locate() uses.
bool triangle_contains(const std::array<Point2, 3>& triangle, double x, double y) noexcept;

}  // namespace urbanpvs::runtime
