// The in-memory model of a generated city: plain data, no behaviour.
//
// Coordinates are metres in a local frame whose origin is the city's south-west corner
// (CityParams::origin_x/origin_y in EPSG:31256), x east, y north, z up. Every coordinate and
// height is a whole number of millimetres (stored as the nearest double), so that walls shared by
// neighbouring buildings have bit-identical vertices and the writers print exact values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "urbanpvs/cities/Params.hpp"

namespace urbanpvs::cities {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

/// A closed ring; the first vertex is not repeated at the end.
using Ring = std::vector<Vec2>;

/// A polygon with holes. The outer ring is counter-clockwise seen from above, holes clockwise.
struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

enum class SurfaceType : std::uint8_t { Ground, Wall, Roof };

/// One planar face of a solid: rings of indices into Solid::vertices (first ring outer, then
/// holes), oriented counter-clockwise seen from outside the solid, as CityJSON requires.
struct Face {
  SurfaceType type = SurfaceType::Wall;
  std::vector<std::vector<std::uint32_t>> rings;
};

/// A closed 2-manifold boundary: every edge is used by exactly two faces, in opposite directions.
struct Solid {
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
};

enum class RoofKind : std::uint8_t {
  Flat,    ///< ridge_height == eaves_height
  Gabled,  ///< two slopes meeting at a ridge; gable walls are pentagons
  Hipped,  ///< slopes on every side (also the closed ring roof of a courtyard building)
};

/// One volume of a composite building (e.g. a tower standing on a podium).
struct BuildingPart {
  std::string id;  ///< "<building id>-p<k>"
  Polygon footprint;
  double eaves_height = 0.0;  ///< metres above ground_z of the parent building
  double ridge_height = 0.0;  ///< metres above ground_z; == eaves_height when flat
  RoofKind roof = RoofKind::Flat;
  int levels = 1;
  Solid solid;
};

struct Building {
  std::string id;           ///< stable id, "blk0042-b03" (block 42, building 3 of that block)
  std::uint32_t block = 0;  ///< index into City::blocks
  /// The whole building's ground outline. Footprints of different buildings never overlap in
  /// area; neighbours in a block share their common wall with identical vertices.
  Polygon footprint;
  double ground_z = 0.0;      ///< lowest terrain under the building (0 on flat ground)
  double eaves_height = 0.0;  ///< metres above ground_z where walls meet the roof (lowest eaves)
  double ridge_height = 0.0;  ///< metres above ground_z of the highest point (== eaves if flat)
  RoofKind roof = RoofKind::Flat;
  int levels = 1;  ///< storeys above ground
  /// The geometry (LoD1 or LoD2 solid) of a simple building; empty when `parts` is not.
  Solid solid;
  /// Composite buildings: the parts carry the geometry, eaves/ridge above are their maxima.
  std::vector<BuildingPart> parts;
};

enum class BlockKind : std::uint8_t {
  Perimeter,  ///< 1-12 buildings around a courtyard
  Solid,      ///< 1-8 buildings covering the whole block, some with light wells (holes)
  Park,       ///< a square or park: no buildings
  Tower,      ///< one high-rise (40-80 m), sometimes on a podium (a composite building)
};

/// A city block: the land between streets.
struct Block {
  std::string id;  ///< "blk0042"
  BlockKind kind = BlockKind::Park;
  Ring lot;  ///< convex, counter-clockwise: the building line along the surrounding streets
  std::uint32_t first_building = 0;  ///< index into City::buildings
  std::uint32_t building_count = 0;
};

/// The river crossing the city: a straight band free of buildings from one edge of the city to
/// another (Wonka's long open view).
struct OpenStrip {
  Vec2 from;                 ///< centre line, where it enters the city square
  Vec2 to;                   ///< centre line, where it leaves the city square
  double water_width = 0.0;  ///< metres, 40-80
  double open_width = 0.0;   ///< metres between the nearest building lines (water plus quays)
};

/// The ground of a hilly city (CityParams::hills > 0): heights at the nodes of a square grid,
/// row by row from the south-west corner `origin`; each grid square is two triangles, split
/// along its south-west to north-east diagonal. Empty for a flat city.
struct Terrain {
  Vec2 origin;
  double spacing = 0.0;  ///< metres between nodes
  int columns = 0, rows = 0;
  std::vector<double> heights;  ///< columns * rows, whole millimetres
  bool empty() const { return heights.empty(); }
  double at(int i, int j) const { return heights[static_cast<std::size_t>(j) * columns + i]; }
};

struct City {
  CityParams params;
  double side = 0.0;  ///< side length of the square city, metres; all geometry is in [0, side]²
  std::vector<Block> blocks;
  std::vector<Building> buildings;
  OpenStrip river;
  Terrain terrain;
};

}  // namespace urbanpvs::cities
