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

#include "urbanpvs/geometry/city/Polygon2.hpp"

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

/// A volume certainly inside a building under one of its roof faces: the prism over `footprint`
/// from `ground_z` up to the plane z(p) = z0 + slope·(p − origin), which lies nowhere above the
/// face (thesis 7.1). Read with ReadOptions::sloped_roofs (RoofPrisms.hpp); its top edges cast
/// the shadows of sloped edges (thesis 4.2.1) once shrunk (RoofPlaneOccluders.hpp).
struct RoofPrism {
  Polygon footprint;
  double ground_z = 0;
  Vec2 origin{0, 0};
  double z0 = 0;
  Vec2 slope{0, 0};  ///< 0: a flat roof face above the part's lowest roof point

  double top_at(Vec2 p) const {
    return z0 + slope.x * (p.x - origin.x) + slope.y * (p.y - origin.y);
  }
};

/// A triangle in absolute coordinates (terrain).
struct Triangle3 {
  std::array<Vec3, 3> v;
};

/// One planar surface of the input as it was given (absolute coordinates, local frame): the
/// outer ring first, then its holes; rings are open (the first point is not repeated).
/// urbanpvs-validate builds its ground truth from these, never from the occluders derived from
/// them, so a mistake in deriving occluders cannot hide itself.
struct Surface3 {
  std::vector<std::vector<Vec3>> rings;
  /// False for a surface that bounds where the building may be, not where it surely is (a roof
  /// of unknown shape above the eaves): a target of validation, never a blocker.
  bool blocks = true;
  /// Which part of its building the surface bounds: for CityJSON and CityGML the building's
  /// parts in file order (0: the Building itself), kInstallation for an installation's; 0 for
  /// input read as prisms. The 3D route shrinks parts alone where the whole does not close.
  std::uint32_t part = 0;
  static constexpr std::uint32_t kInstallation = 0xFFFFFFFFu;
};

/// One building (with all its parts): the unit a PVS lists.
struct CityObject {
  std::uint32_t index = 0;  ///< stable: position in City::objects, in input order
  std::string source_id;    ///< CityJSON key, GeoJSON id / properties.id / @type/@id, or #<n>
  /// The value of the input's attribute, property or tag ReadOptions::payload_key names: a
  /// string as given, a number or boolean as JSON text; empty when it has none.
  std::string payload;
  std::vector<Polygon> footprint;        ///< ground footprint of every part reaching the ground
  double ground_z = 0;                   ///< lowest point of the object
  Box3 bbox;                             ///< of all its geometry, parts above the ground included
  std::vector<OccluderPrism> occluders;  ///< may be empty (e.g. only raised parts)
  /// With ReadOptions::sloped_roofs: the prisms under the roof faces that rise above the parts'
  /// occluders (CityJSON and CityGML faces; GeoJSON and OSM roof:shape, RoofShapes.hpp).
  std::vector<RoofPrism> roof_prisms;
  /// The input's own surfaces of this object: CityJSON, every surface of the chosen LoD of the
  /// building, its parts and installations; GeoJSON, the walls, top and bottom of each part's
  /// prism from its base to its full height (the roof's top), and where roof:shape gives the
  /// roof, its faces and the walls above the eaves (RoofShapes.hpp).
  std::vector<Surface3> surfaces;
  /// False when the object cannot be an occluder (geometry beyond repair, no height): it has no
  /// occluders and its surfaces block nothing in validation, but it is still listed, tested
  /// for visibility over its whole box (as tall as it may be), and its footprint (or box) is
  /// still taken out of free space, so no view cell lies inside it.
  bool occludes = true;
};

/// A triangulated terrain (CityJSON TINRelief, or a DEM given with --terrain), absolute heights.
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
  std::size_t default_heights = 0;  ///< objects whose height came from --default-height
  std::size_t level_heights = 0;    ///< heights from building:levels x level height
  /// CityJSON parts on the ground without GroundSurface whose footprint is the projection of
  /// their upward surfaces, checked to lie within their walls (no eaves overhang).
  std::size_t footprints_from_roof = 0;
  /// Such parts whose roof overhangs the walls: footprint from the walls' bottom edges instead.
  std::size_t footprints_from_walls = 0;
  /// Such parts whose walls give no closed footprint either: no occluder (conservative).
  std::size_t footprints_unknown = 0;
  /// CityJSON/CityGML parts with a GroundSurface that walls do not stand round (walls missing
  /// from the file): no occluder.
  std::size_t grounds_off_walls = 0;
  /// CityJSON parts off the ground (on an OuterCeilingSurface, or floating): no occluder.
  std::size_t raised_parts = 0;
  /// GeoJSON buildings and parts whose occluder was cut from `height` down to the eaves.
  std::size_t roof_eaves = 0;
  /// GeoJSON buildings and parts whose roof:shape gave the roof's faces (RoofShapes.hpp).
  std::size_t roof_shapes = 0;
  /// GeoJSON buildings and parts that are roofs on open sides (building=roof): no occluder.
  std::size_t open_roofs = 0;
  /// GeoJSON objects set on the terrain (TINRelief) of a CityJSON file read with them.
  std::size_t on_terrain = 0;
  /// OpenStreetMap buildings and parts assembled from multipolygon relations.
  std::size_t osm_multipolygons = 0;
  /// BuildingInstallations (and other non-part children) merged into their building.
  std::size_t installations = 0;
  /// Every repair that changed geometry, one line each: "file: id: what was done".
  std::vector<std::string> repairs;
  /// Every object kept without occluders, one line each: "file: id: why".
  std::vector<std::string> non_occluding;
  std::vector<std::string> warnings;
  std::string coordinate_note;  ///< how the CRS / lon-lat decision was made
  std::string terrain_note;     ///< where the terrain came from and how it was resampled
};

/// A street or path as the input maps it: its centre line (local frame) and its width.
struct StreetLine {
  std::string id;  ///< "w123" for an OpenStreetMap way
  std::vector<Vec2> points;
  double width = 0;  ///< [Units: m]
};

/// Where people can be: centre lines with their widths, and areas (street surfaces,
/// pedestrian zones, squares). Both may overlap each other and buildings.
struct StreetNetwork {
  std::vector<StreetLine> lines;
  std::vector<Polygon> areas;
  bool empty() const { return lines.empty() && areas.empty(); }
};

struct City {
  LocalFrame frame;
  std::vector<CityObject> objects;
  Terrain terrain;
  /// Where people can be, as the input maps it (OpenStreetMap); empty for inputs that map no
  /// streets. The view cells place cells on it with --cells streets.
  StreetNetwork streets;
  ReadReport report;
  std::vector<std::string> sources;  ///< files read, in order
  /// ReadOptions::payload_key the objects' payloads were read with (empty: none).
  std::string payload_key;

  Box3 bounds() const {
    Box3 b;
    for (const CityObject& o : objects) b.extend(o.bbox);
    return b;
  }
};

}  // namespace urbanpvs::geometry
