// SPDX-License-Identifier: GPL-3.0-or-later
// Terrain from a digital elevation model (--terrain FILE): any raster GDAL reads (GeoTIFF, SRTM
// .hgt, ...), reprojected and resampled into the city's local frame as a regular TIN. It is the
// ground that GeoJSON and OpenStreetMap buildings stand on and that view cells follow (thesis
// 5.3: a cell spans the eye band above the ground under it).
#pragma once

#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// What resampling did, for the reading report.
struct DemSummary {
  std::string driver;  ///< GDAL's short name: "GTiff", "SRTMHGT"
  std::string crs;     ///< the raster's reference system, e.g. "EPSG:4326"
  int raster_columns = 0, raster_rows = 0;
  double pixel_x = 0, pixel_y = 0;    ///< the raster's pixel in the local frame [Units: m]
  double spacing = 0;                 ///< the TIN's grid spacing [Units: m]
  int columns = 0, rows = 0;          ///< TIN grid nodes
  std::size_t filled = 0;             ///< nodes on voids or off the raster, filled from neighbours
  double zmin = 0, zmax = 0;          ///< heights of the TIN
  std::vector<std::string> warnings;  ///< "file: problem", for ReadReport::warnings
};

/// Reads band 1 of the raster at `path` and resamples it, bilinearly between pixel centres,
/// onto a grid over `area` (local frame of `frame`) at half the raster's pixel, coarser where
/// that would exceed a few million nodes. Nodes on no-data pixels or off the raster take the
/// mean of their known neighbours, repeated outwards (a void is bridged by the ground around it;
/// the ground only places buildings and cells, it hides nothing). The raster's heights are taken
/// as absolute heights in the city's vertical datum.
///
/// Throws InputError naming `path`: Unreadable (10) for a missing file, UnsupportedFormat (17)
/// for one GDAL cannot read as a georeferenced raster, UnknownCrs (13) when the raster's and
/// the city's reference systems cannot be related or the raster covers none of `area`.
Terrain read_dem_terrain(const std::string& path, const LocalFrame& frame, const Box2& area,
                         DemSummary* summary = nullptr);

}  // namespace urbanpvs::geometry
