// SPDX-License-Identifier: GPL-3.0-or-later
// Input whose coordinates are not metres as they stand (feet, Mercator, degrees on another datum
// than WGS84), transformed into WGS84 lon/lat before it is read (InputReprojection.cpp).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "CityReaders.hpp"
#include "GdalHandles.hpp"

namespace urbanpvs::geometry::detail {

struct Reprojection {
  std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> to_wgs84;
  double z_to_metres = 1;  ///< heights in the input's unit (a projection in feet: feet)
  std::string from;        ///< "EPSG:2263 (in US survey foot)", for the reading's note
};

/// True when coordinates in `s` are metres as they stand: a projection in metres that is no
/// Mercator. Everything else a reader transforms with reprojection_from.
bool is_metric_projection(const OGRSpatialReference& s);

/// "EPSG:n" where `s` names that code or PROJ's catalogue matches it with confidence (a system
/// given as WKT only), else its own authority and code ("ESRI:102100"); "" when it has neither.
std::string authority_code(const OGRSpatialReference& s);

/// The transformation from `s` into WGS84 lon/lat, for coordinates that are not metres
/// (is_metric_projection false). `name` is how the reading's note names `s`. Throws
/// InputError(UnknownCrs) naming `file` and `object` for a system that is neither projected nor
/// geographic, or one PROJ cannot transform.
Reprojection reprojection_from(const OGRSpatialReference& s, const std::string& name,
                               const std::string& file, const std::string& object);

/// A reference system's name that is no EPSG URL, URN or code: Swiss "CH1903" and "CH1903+"
/// (the LV03 and LV95 grids), else as GDAL identifies it without reading files or the network:
/// "EPSG:n" where the EPSG catalogue holds it, else its own authority and code ("ESRI:102100",
/// Esri's Web Mercator); "" when neither knows it.
std::string identify_crs(const std::string& name);

/// The transformation into WGS84 lon/lat for input in `crs` (normalise_crs's name), or nullopt
/// where its coordinates are metres already: no system, WGS84 lon/lat, a projection in metres
/// other than a Mercator, or a system GDAL does not know (taken as metres, as the file says
/// nothing else). Throws InputError(UnknownCrs) for a system that is neither projected nor
/// geographic, or one PROJ cannot transform.
std::optional<Reprojection> reprojection_for(const std::string& crs, const std::string& file);

/// True when a GML file in `crs` (normalise_crs's name) writes latitude first: the geographic
/// systems whose EPSG axis order is latitude, longitude (EPSG:4326, 4979, 4258, 6697, ...).
bool latitude_first(const std::string& crs);

/// Rewrites a CityJSON document's vertices (after its "transform"; heights into metres) and a
/// GeoJSON document's positions (its heights are properties, in metres already) into WGS84
/// lon/lat, and names WGS84 as their system. Throws
/// InputError naming `file` for a vertex that is not three numbers or one PROJ cannot transform.
void reproject_cityjson(Json& doc, Reprojection& r, const std::string& file);
void reproject_geojson(Json& doc, Reprojection& r, const std::string& file);

}  // namespace urbanpvs::geometry::detail
