// SPDX-License-Identifier: GPL-3.0-or-later
// Building blocks (thesis 5.4, 7.3.3): touching buildings fused into one stepped height field, so
// that a row of connected houses occludes as one wall instead of a row of walls with ε-wide
// slits between them after shrinking.
#pragma once

#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// The limits of every option are those of block_settings() (BlockSettings.hpp).
struct BlockOptions {
  /// Footprints closer than this (m) fuse, and gaps narrower than it inside a block are closed
  /// (like Umbra's "smallest hole"). Shared walls in real data are often not bit-identical; the
  /// default closes the slivers of digitizing noise, yet no slit a person could see through.
  /// [Units: m]
  double gap_tolerance = 0.05;
  /// Occluder tops are rounded *down* to a multiple of this (conservative: lower occluders hide
  /// less), which merges near-equal heights into one level. 0 keeps exact heights.
  /// [Units: m]
  double height_step = 0.1;
  /// Each level's outline is simplified within this distance before it is shrunk, and shrunk by
  /// as much more (BlockLevel::grown_by). Fused walls that are not bit-identical in the data
  /// leave near-collinear vertices a fraction of a millimetre apart; the straight skeleton then
  /// falls back to exact arithmetic on every event, and shrinking took 90% of the scene build
  /// (39 s of 42 s on a generated 4 km² city; 3.2 s with 1 mm). 0 keeps every vertex.
  /// [Units: m]
  double outline_tolerance = 0.001;
  /// The terrain (a TINRelief, or a DEM given with --terrain) occludes as stepped levels this
  /// far apart, each the ground where the terrain is certainly at least that high, eroded by ε
  /// (TerrainOccluders.hpp). 0, the default: the terrain hides nothing. Off by default for its
  /// price where it gains little (README, "Terrain as an occluder"): on Monaco's DEM, whose
  /// buildings mostly have no height, 8 m levels made the bake 5.9x slower for 3.6 % off the
  /// mean PVS; on a generated hilly city they took 9.7 % off it at 13 % more time.
  /// [Units: m]
  double terrain_step = 0;
  /// The terrain occludes as sloped prisms over squares of this side, each top a plane along
  /// the terrain's mean gradient over the square, lowered under the terrain within ε
  /// (TerrainOccluders.hpp, terrain_plane_occluders): crests and hillsides cast the shadows of
  /// sloped edges (thesis 4.2.1). 0, the default: off (README, "Terrain as an occluder").
  /// [Units: m]
  double terrain_planes = 0;
  /// Buildings that are not height fields (a face looks down from above the ground: arcades,
  /// overhangs, bridges) are also shrunk in 3D (thesis 7.3.1: the outside meshed into
  /// tetrahedra by TetGen, each enlarged by ε) into ground-standing levels this far apart
  /// (SolidOccluders.hpp), which join the blocks' occluders. Height fields are left to the
  /// blocks, which lose less (README, "Shrinking solids in 3D"). 0, the default: off. Needs a
  /// build with URBANPVS_TETGEN=ON (AGPL).
  /// [Units: m]
  double solid_step = 0;
};

/// One step of a block's height field: everything of the block at least `top_z` high.
struct BlockLevel {
  double top_z = 0;  ///< absolute height of this level's roof plane
  /// Union of the footprints of the occluders reaching top_z, each first grown by half the gap
  /// tolerance (mitred offset) so that gaps narrower than it close, then simplified within the
  /// outline tolerance. Whoever erodes it must erode by `grown_by` more (see shrink_blocks):
  /// straight-skeleton offsets compose, and what the simplification added lies within its
  /// tolerance of the boundary, so eroding the region by ε + grown_by stays inside the real
  /// footprints wherever no gap was closed.
  std::vector<Polygon> region;
  double grown_by = 0;  ///< [Units: m]
};

struct Block {
  std::vector<std::uint32_t> objects;  ///< sorted object indices fused into this block
  std::vector<BlockLevel> levels;      ///< ascending top_z; each region contains the next one's
  Box2 bounds;
};

/// Groups the occluder prisms of all objects into blocks and builds their levels. Deterministic:
/// blocks are ordered by their smallest object index.
std::vector<Block> build_blocks(const std::vector<CityObject>& objects,
                                const BlockOptions& options);

}  // namespace urbanpvs::geometry
