// SPDX-License-Identifier: GPL-3.0-or-later
// A user-drawn region for the view cells (e.g. the streets a game level lets the player walk),
// read from GeoJSON in the same coordinate reference system as the city.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// Reads every Polygon and MultiPolygon in a GeoJSON document (a bare geometry, a Feature, a
/// FeatureCollection or a GeometryCollection) and maps it into the city's local frame. A "crs"
/// member, when present, must name the city's CRS. Throws InputError (Unreadable, InvalidJson,
/// BadStructure, UnknownCrs, InvalidGeometry, EmptyCity when there is no polygon) naming `path`.
std::vector<Polygon> read_region_file(const std::string& path, const LocalFrame& frame);

/// The same for text in memory; `name` stands for the file in messages.
std::vector<Polygon> read_region_text(std::string_view text, const std::string& name,
                                      const LocalFrame& frame);

}  // namespace urbanpvs::geometry
