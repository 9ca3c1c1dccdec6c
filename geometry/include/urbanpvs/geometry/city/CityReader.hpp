// SPDX-License-Identifier: GPL-3.0-or-later
// Reads city models into a City: CityJSON, CityGML, GeoJSON, OpenStreetMap and the vector
// formats of GIS (Shapefile, GeoPackage, FlatGeobuf) through GDAL.
// The format is recognised from the content, not the extension.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// How a city is read. The limits of every option are those of read_settings()
/// (ReadSettings.hpp), the table every tool binds.
struct ReadOptions {
  /// Height (m) of GeoJSON buildings that carry no height attribute. Unset: such a building is
  /// an InputError(MissingHeight).
  std::optional<double> default_height;
  /// Height of one storey (m) for building:levels / building:min_level.
  double level_height = 3.0;
  /// How GeoJSON coordinates are read; Auto decides from the "crs" member, else from the range.
  enum class Coordinates { Auto, Geographic, Projected } coordinates = Coordinates::Auto;
  /// Refuse input that needs geometric repair (InputError(InvalidGeometry)) instead of
  /// repairing it, or keeping a building beyond repair as a non-occluding object.
  bool strict = false;
  /// The tallest plausible building above its ground. Taller input is refused
  /// (InputError(Implausible)); objects of unknown height are tested for visibility up to it,
  /// as tall as they may be. [Units: m]
  double max_height = 1000.0;
  /// The largest plausible extent of a city (either side of its bounding rectangle); larger
  /// input is refused (InputError(Implausible)) rather than baked for hours. [Units: m]
  double max_extent = 300000.0;
  /// The attribute (CityJSON), property (GeoJSON) or tag (OpenStreetMap) whose value each
  /// object carries as its payload (CityObject::payload): a key a renderer finds its mesh or
  /// tile by. Empty: no payloads.
  std::string payload_key;
  /// GeoJSON property, GIS field or OSM tag that holds each building's height (a length, as
  /// `height`: "12", "12.5 m", "40 ft"), tried before height, building:height and
  /// measuredHeight. For datasets that name it their own way ("HOEHE", "h_max"). Empty: none.
  std::string height_field;
  /// The layer of a GIS vector file (GeoPackage, ...) to read. Empty: the only layer of
  /// polygons; a file with several must be told which.
  std::string layer;
  /// A digital elevation model (any raster GDAL reads: GeoTIFF, SRTM .hgt) that becomes the
  /// city's terrain (DemTerrain.hpp), replacing a CityJSON TINRelief: GeoJSON and OpenStreetMap
  /// buildings stand on it and view cells follow it. Empty: none.
  std::string terrain_path;
  /// CityJSON parts: set, the occluder is a stepped height field under the part's own surfaces
  /// (SteppedRoof.hpp), with a level at each surface's lowest point and, on sloped roofs,
  /// every roof_step above it; levels closer than that merge (0: no levels between a sloped
  /// roof's eaves and its top). Unset: one prism per part, cut at the lowest point of its
  /// roof. [Units: m]
  std::optional<double> roof_step;
  /// CityJSON parts: each roof face that rises above the part's occluder adds the prism under
  /// its own plane (RoofPrisms.hpp), whose sloped top edges cast their own shadows (thesis
  /// 4.2.1): a gabled roof occludes up to near its ridge with four walls per face, not with a
  /// level every roof_step. On by default (since 2026-12-05): the design shrinks roofs as
  /// height fields (thesis 7.3.2, 7.4), and on real LoD2 data the faces cut the mean PVS by a
  /// third for about twice the visibility time (README, "Roofs with their slopes"). Input
  /// without faces above the eaves (LoD1, GeoJSON, OSM) is read as before.
  bool sloped_roofs = true;
};

/// Reads every file into one city (all files must share one coordinate reference system).
/// Throws InputError naming the file, the feature and the problem.
City read_city(const std::vector<std::string>& paths, const ReadOptions& options = {});

/// Reads a city from text held in memory; `name` stands for the file in messages.
City read_city_text(std::string_view text, const std::string& name,
                    const ReadOptions& options = {});

}  // namespace urbanpvs::geometry
