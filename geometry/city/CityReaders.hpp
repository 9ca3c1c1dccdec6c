// SPDX-License-Identifier: GPL-3.0-or-later
// Internal interface between read_city and the per-format readers. Each format is read in two
// steps: scan (reference system and extent, to choose the local frame) and load (objects).
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

namespace osmium::memory {
class Buffer;
}  // namespace osmium::memory

namespace urbanpvs::geometry::detail {

// ordered_json keeps the file's order, which makes object indices follow the input.
using Json = nlohmann::ordered_json;

struct InputScan {
  LocalFrame::Kind kind = LocalFrame::Kind::Projected;
  std::string crs;  ///< normalised ("EPSG:7415", "OGC:CRS84") or empty
  Box2 bounds;      ///< in input coordinates
  std::string note;
};

/// Normalises a CRS name or URL (OGC URL, URN, "EPSG:n") to "EPSG:n" or "OGC:CRS84"; throws
/// InputError(UnknownCrs) for anything else.
/// The whole file; InputError (Unreadable) naming it when it is missing, not a regular file or
/// cannot be read.
std::string read_input_file(const std::string& path);
/// The same checks without reading: the file opened, for readers that read it themselves.
std::ifstream open_input_file(const std::string& path);

std::string normalise_crs(const std::string& name, const std::string& file);
bool is_geographic_crs(const std::string& normalised);

/// The readable part of a JSON parser's message ("parse error at line L, column C: ...").
std::string json_error_text(const nlohmann::json::exception& e);

/// A JSON text sequence (JsonSequence.cpp) joined into one document: a CityJSON header line
/// and one CityJSONFeature per line into a CityJSON document, one GeoJSON Feature per line into
/// a FeatureCollection; nullopt when `text` is neither. Throws InputError naming the line of an
/// item that is no JSON or not of the sequence's kind.
std::optional<Json> join_json_sequence(std::string_view text, const std::string& file);

/// True when `text` is XML: its first character other than a byte order mark or white space
/// is '<'.
bool is_xml(std::string_view text);
/// A CityGML file's buildings and building parts as a CityJSON document (CityGmlReader.cpp);
/// throws InputError: InvalidXml (line and column) for malformed XML, BadStructure for a
/// coordinate list that is no list of 2D or 3D points.
Json citygml_to_cityjson(std::string_view text, const std::string& file);
/// The member of a city object in citygml_to_cityjson's document that says why a polygon of it
/// could not be read (a coordinate list that is no whole number of points), or of a feature in
/// read_osm's document why its area could not be built: the CityJSON and GeoJSON readers keep
/// such a building, over the box of its positions, as an object that occludes nothing
/// (--strict refuses it).
inline constexpr const char* kUnreadableMember = "urbanpvs:unreadable";

/// Replaces every GeometryInstance of a CityJSON document by its template's geometry, placed by
/// its matrix at its reference vertex, with vertices of its own appended to "vertices"
/// (GeometryTemplates.cpp). Throws InputError(BadStructure) naming the object for an instance
/// that names no template, no reference vertex or no matrix of 16 numbers.
void expand_geometry_instances(Json& doc, const std::string& file);

InputScan scan_cityjson(const Json& doc, const std::string& file);
void load_cityjson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                   const ReadOptions& options, City& city);

InputScan scan_geojson(const Json& doc, const std::string& file, const ReadOptions& options);
void load_geojson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                  const ReadOptions& options, City& city);

/// "12", "12.5 m", "12,5m", "40 ft", "40'" -> metres; nullopt when it is no length.
std::optional<double> parse_length(const Json& v);

/// The member of read_osm's document that lists where people can be: objects with an "id" and
/// either a "line" (lon/lat positions, with the way's "highway", "width", "est_width" and
/// "lanes" tags where given) or an "area" (a GeoJSON polygon: rings of lon/lat positions).
inline constexpr const char* kStreetsMember = "urbanpvs:streets";

/// read_osm's kStreetsMember in the local frame (OsmStreets.cpp): each line with its width in
/// metres (width, est_width, else lanes, else its highway class), areas repaired.
StreetNetwork osm_streets(const Json& streets, const std::string& file,
                          const LocalFrameMapping& mapping, ReadReport& report);

/// True when `path` ends in `ext` (lower case), whatever the case of the path's letters.
bool has_extension(const std::string& path, const char* ext);

/// True for the names of OpenStreetMap files (.osm.pbf, .pbf, .osm, .osm.gz, .osm.bz2).
bool is_osm_file(const std::string& path);
/// An OpenStreetMap file's buildings and building parts as a GeoJSON FeatureCollection in
/// lon/lat (OsmReader.cpp): ids "w123" / "r456", tags as properties. Assembly problems (broken
/// multipolygons, members outside the extract) go to report.warnings, per element id.
Json read_osm(const std::string& path, ReadReport& report);
/// OpenStreetMap objects already read (Overpass JSON), in any order and with ids repeated,
/// as read_osm gives them: sorted, each id at its newest version, assembled. Problems are
/// reported naming `file`.
Json assemble_osm(osmium::memory::Buffer&& objects, const std::string& file, ReadReport& report);

/// True for an Overpass API JSON document (`[out:json]`): an object with an "elements" array
/// and no GeoJSON or CityJSON "type".
bool is_overpass_json(const Json& doc);
/// An Overpass API JSON document's buildings as read_osm gives them (OverpassJson.cpp): nodes,
/// ways and relations as the API writes them with "out body", "out skel" or "out geom" (way and
/// member geometries inline). Throws InputError(BadStructure) naming the element at fault.
Json read_overpass_json(const Json& doc, const std::string& file, ReadReport& report);

/// True for the names of the GIS vector files read through GDAL (.shp, .shz, .shp.zip, .gpkg,
/// .fgb, .tab, .sqlite), whatever their case.
bool is_gis_vector_file(const std::string& path);
/// One layer of a GIS vector file (GisVectorReader.cpp) as a GeoJSON FeatureCollection: the
/// layer options.layer names, else the only one of polygons (InputError BadStructure when there
/// are several, EmptyCity when there is none). Fields become properties; coordinates stay in a
/// projected system in metres with an EPSG code and are transformed to WGS84 lon/lat from any
/// other (noted in report.warnings). Features without polygons are left out and counted there.
Json read_gis_vector(const std::string& path, const ReadOptions& options, ReadReport& report);

/// Turns `o` into a non-occluding object: no occluders, its surfaces block nothing in
/// validation, its footprint (its box's rectangle when it has none) is taken out of free space
/// (no view cell inside a building), and `why` is listed in report.non_occluding.
CityObject non_occluding(CityObject o, const std::string& why, ReadReport& report);

/// Throws InputError(Implausible) for a building taller than options.max_height.
void check_plausible(const CityObject& o, const ReadOptions& options, const std::string& file);

/// An object's payload (ReadOptions::payload_key): member `key` of `attributes` (CityJSON
/// attributes, GeoJSON properties, OSM tags), a string as given and any other value as compact
/// JSON text; "" when `key` is empty, the member is absent or null (never throws).
std::string payload_of(const Json& attributes, const std::string& key);

/// The string member `key` of `obj`, or "" when absent or not a string (never throws).
std::string string_member(const Json& obj, const char* key);

/// Reads a number from JSON, throwing InputError(BadStructure) naming `what` otherwise.
double json_number(const Json& v, const std::string& file, const std::string& feature,
                   const char* what);

}  // namespace urbanpvs::geometry::detail
