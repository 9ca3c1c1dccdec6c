// SPDX-License-Identifier: GPL-3.0-or-later
// The terrain as occluders (thesis 7.3.2, 7.4): the earth under a TIN is a 2.5D height field,
// and a stepped field below it, a level every `step` metres, is a set of nested prisms like a
// block's levels. Each level is the ground where the terrain is certainly at least that high,
// eroded by ε, so whatever it hides from a sample stays hidden from every viewpoint within ε.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"

namespace urbanpvs::geometry {

/// Occluder::block of a terrain occluder: it comes from no block.
inline constexpr std::uint32_t kTerrainBlock = 0xFFFFFFFFu;

/// The squares the terrain is cut into, and how many of them make a tile.
struct TerrainRaster {
  Box2 area;          ///< the squares' extent: `area` of terrain_occluders, snapped outwards
  double square = 0;  ///< [Units: m]
  int columns = 0, rows = 0;
  /// Per square, row-major: the lowest point of the terrain over the square (its TIN clipped
  /// to it), or -infinity where the TIN does not cover the whole square.
  std::vector<double> lowest;

  /// Square (i, j)'s lowest terrain; -infinity outside the raster (no ground known there).
  double lowest_at(int i, int j) const {
    if (i < 0 || j < 0 || i >= columns || j >= rows)
      return -std::numeric_limits<double>::infinity();
    return lowest[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) +
                  static_cast<std::size_t>(i)];
  }
};

/// The lowest terrain over each square of side `square` covering `area` (at most kMaxSquares
/// of them: the side grows to fit). Exact: each triangle is clipped to each square it overlaps.
TerrainRaster terrain_raster(const Terrain& terrain, const Box2& area, double square);

/// The terrain's occluders over `area` (the objects' extent: terrain elsewhere hides nothing
/// worth a bake): for every multiple h of `step` (m, > 0), the squares whose lowest terrain is
/// at least h, eroded by `epsilon` (m, > 0) with a square of half-side ε (a subset of the
/// erosion by the disk of radius ε), as rectilinear prisms of height h, cut into tiles of
/// about 128 m so that a map near a cell clips few of their edges. A level equal to the one
/// above it in a tile hides nothing more and is left out. Every point p of an occluder of top h
/// has the terrain at least h everywhere within ε of p (horizontally): the shrunk field of
/// issue 17, f(q) >= f'(p) for |q - p| <= ε.
std::vector<Occluder> terrain_occluders(const Terrain& terrain, const Box2& area, double step,
                                        double epsilon);

/// The terrain's occluders over `area` as sloped prisms, one per square of side `square` (m,
/// > 0; grown to stay within the raster's limit): each square's top is a plane along the mean
/// gradient of the terrain over the square, lowered until, for every point p of the square and
/// every q within `epsilon` (m, > 0) of p horizontally, the terrain at q is at least the plane
/// at p (the 2.5D erosion of thesis 7.4: f(q) >= f'(p) for |q - p| <= ε). The edges of the
/// squares are sloped edges that cast the shadows of thesis 4.2.1: crests and hillsides hide
/// what lies behind them. A square whose ε-surroundings the TIN does not wholly cover gets none.
std::vector<Occluder> terrain_plane_occluders(const Terrain& terrain, const Box2& area,
                                              double square, double epsilon);

}  // namespace urbanpvs::geometry
