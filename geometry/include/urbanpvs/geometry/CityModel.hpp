// SPDX-License-Identifier: GPL-3.0-or-later
// The city model: what every reader produces and every later stage consumes. Coordinates are in a
// local metric frame (east, north, up) whose relation to the input is kept in LocalFrame, so a PVS
// file can map its cells back to the input's coordinates.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "urbanpvs/geometry/Polygon2.hpp"

namespace urbanpvs::geometry {

/// How local coordinates relate to the input's.
struct LocalFrame {
  enum class Kind {
    Projected,   ///< input in a metric CRS; local = input - origin
    Geographic,  ///< input in WGS84 lon/lat; local = east/north/up around origin_lon/lat/h
  };
  Kind kind = Kind::Projected;
  std::string crs;                 ///< e.g. "EPSG:7415"; empty when the input names none
  std::array<double, 3> origin{};  ///< projected: input coordinates of the local origin
  double origin_lon = 0, origin_lat = 0, origin_h = 0;  ///< geographic: WGS84 origin
};

/// A volume that is certainly inside a real building: the prism over `footprint` from
/// `ground_z` up to `top_z` (absolute heights). Thesis 7.1: occluders must be a subset of the
/// building, so `top_z` is the lowest roof point (eaves, not ridge) of the part it comes from.
struct OccluderPrism {
  Polygon footprint;
  double ground_z = 0;
  double top_z = 0;
};

/// A triangle in absolute coordinates (terrain).
struct Triangle3 {
  std::array<std::array<double, 3>, 3> v;
};

/// One building (with all its parts): the unit a PVS lists.
struct CityObject {
  std::uint32_t index = 0;   ///< stable: position in City::objects, in input order
  std::string source_id;     ///< CityJSON key, GeoJSON id / properties.id / @type/@id, or #<n>
  std::vector<Polygon> footprint;  ///< ground footprint of every part reaching the ground
  double ground_z = 0;       ///< lowest point of the object
  Box3 bbox;                 ///< of all its geometry, parts above the ground included
  std::vector<OccluderPrism> occluders;  ///< may be empty (e.g. only raised parts)
};

/// A triangulated terrain (CityJSON TINRelief), absolute heights.
struct Terrain {
  std::vector<Triangle3> triangles;
  bool empty() const { return triangles.empty(); }
};

/// What reading did besides producing objects: shown to the user, never silent.
struct ReadReport {
  std::map<std::string, std::size_t> ignored_types;  ///< city object type -> count
  std::size_t repaired_duplicate_points = 0;
  std::size_t repaired_orientation = 0;
  std::size_t repaired_unclosed = 0;
  std::size_t default_heights = 0;     ///< objects whose height came from --default-height
  std::size_t level_heights = 0;       ///< heights from building:levels x level height
  std::size_t footprints_from_roof = 0;  ///< LoD2 parts without ground surface
  std::size_t skipped_invalid = 0;     ///< objects dropped (only with skip_invalid)
  std::vector<std::string> warnings;
  std::string coordinate_note;         ///< how the CRS / lon-lat decision was made
};

struct City {
  LocalFrame frame;
  std::vector<CityObject> objects;
  Terrain terrain;
  ReadReport report;
  std::vector<std::string> sources;  ///< files read, in order

  Box3 bounds() const {
    Box3 b;
    for (const CityObject& o : objects) b.extend(o.bbox);
    return b;
  }
};

}  // namespace urbanpvs::geometry
