// SPDX-License-Identifier: GPL-3.0-or-later
// Internal interface between read_city and the per-format readers. Each format is read in two
// steps: scan (reference system and extent, to choose the local frame) and load (objects).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

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

std::string normalise_crs(const std::string& name, const std::string& file);
bool is_geographic_crs(const std::string& normalised);

InputScan scan_cityjson(const Json& doc, const std::string& file);
void load_cityjson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                   const ReadOptions& options, City& city);

InputScan scan_geojson(const Json& doc, const std::string& file, const ReadOptions& options);
void load_geojson(const Json& doc, const std::string& file, const LocalFrameMapping& mapping,
                  const ReadOptions& options, City& city);

/// True for the names of OpenStreetMap files (.osm.pbf, .pbf, .osm, .osm.gz, .osm.bz2).
bool is_osm_file(const std::string& path);
/// An OpenStreetMap file's buildings and building parts as a GeoJSON FeatureCollection in
/// lon/lat (OsmReader.cpp): ids "w123" / "r456", tags as properties. Assembly problems (broken
/// multipolygons, members outside the extract) go to report.warnings, per element id.
Json read_osm(const std::string& path, ReadReport& report);

/// Turns `o` into a non-occluding object: no occluders, its surfaces block nothing in
/// validation, its footprint (its box's rectangle when it has none) is taken out of free space
/// (no view cell inside a building), and `why` is listed in report.non_occluding.
CityObject non_occluding(CityObject o, const std::string& why, ReadReport& report);

/// Throws InputError(Implausible) for a building taller than options.max_height.
void check_plausible(const CityObject& o, const ReadOptions& options, const std::string& file);

/// The string member `key` of `obj`, or "" when absent or not a string (never throws).
std::string string_member(const Json& obj, const char* key);

/// Reads a number from JSON, throwing InputError(BadStructure) naming `what` otherwise.
double json_number(const Json& v, const std::string& file, const std::string& feature,
                   const char* what);

}  // namespace urbanpvs::geometry::detail
