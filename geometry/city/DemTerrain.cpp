// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/DemTerrain.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "GdalHandles.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

namespace urbanpvs::geometry {
namespace {

using detail::crs_name;
using detail::DatasetCloser;
using detail::QuietGdal;
using detail::TransformDeleter;

// The TIN stays within a few hundred MB: 1M nodes are 2M triangles of 72 bytes, held by the city
// and again by the ground model. A 10 km city still gets a 10 m grid.
constexpr double kMaxNodes = 1.0e6;
// Pixels read at full resolution; a larger window is averaged down by GDAL while it is read.
constexpr double kMaxPixels = 32.0e6;
// No grid finer than this: the ground under a viewer does not need centimetres.
constexpr double kMinSpacing = 0.5;  // [Units: m]

// The city's horizontal reference system, as GDAL knows it; false when the city names none.
bool city_crs(const LocalFrame& frame, OGRSpatialReference& s) {
  if (frame.kind == LocalFrame::Kind::Geographic) {
    s.SetWellKnownGeogCS("WGS84");
  } else {
    if (frame.crs.rfind("EPSG:", 0) != 0) return false;
    if (s.importFromEPSG(std::stoi(frame.crs.substr(5))) != OGRERR_NONE) return false;
  }
  // x = easting / longitude, y = northing / latitude, whatever the authority's axis order.
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return true;
}

// Multi-source breadth-first fill: each unknown node takes the mean of the nodes known before
// its ring, so a void is bridged from its rim inwards and the margin off the raster continues
// the raster's edge. Returns how many nodes were filled.
std::size_t fill_unknown(std::vector<double>& z, std::vector<char>& known, int cols, int rows) {
  auto for_neighbours = [&](int i, int j, auto&& f) {
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int a = i + di, b = j + dj;
        if ((di || dj) && a >= 0 && b >= 0 && a < cols && b < rows) f(std::size_t(b) * cols + a);
      }
  };
  std::vector<std::size_t> ring, next;
  std::vector<char> queued(known);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const std::size_t n = std::size_t(j) * cols + i;
      if (known[n]) continue;
      bool touches = false;
      for_neighbours(i, j, [&](std::size_t m) { touches |= known[m] != 0; });
      if (touches) ring.push_back(n), queued[n] = 1;
    }
  std::size_t filled = 0;
  std::vector<double> value;
  while (!ring.empty()) {
    value.assign(ring.size(), 0.0);
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const int i = int(ring[k] % cols), j = int(ring[k] / cols);
      double sum = 0;
      int count = 0;
      for_neighbours(i, j, [&](std::size_t m) {
        if (known[m]) sum += z[m], ++count;
      });
      value[k] = sum / count;
    }
    next.clear();
    for (std::size_t k = 0; k < ring.size(); ++k) {
      z[ring[k]] = value[k];
      known[ring[k]] = 1;
      const int i = int(ring[k] % cols), j = int(ring[k] / cols);
      for_neighbours(i, j, [&](std::size_t m) {
        if (!queued[m]) queued[m] = 1, next.push_back(m);
      });
    }
    filled += ring.size();
    ring.swap(next);
  }
  return filled;
}

}  // namespace

Terrain read_dem_terrain(const std::string& path, const LocalFrame& frame, const Box2& area,
                         DemSummary* summary) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(InputProblem::Unreadable, path, "",
                     std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  if (area.empty()) throw std::invalid_argument("read_dem_terrain: empty area");
  const QuietGdal quiet;
  std::unique_ptr<GDALDataset, DatasetCloser> ds(
      GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds)
    throw InputError(InputProblem::UnsupportedFormat, path, "",
                     "not a raster GDAL can read (GeoTIFF, SRTM .hgt, ...)" + QuietGdal::last());
  if (ds->GetRasterCount() < 1)
    throw InputError(InputProblem::UnsupportedFormat, path, "", "the raster has no band");
  double gt[6], inv[6];
  if (ds->GetGeoTransform(gt) != CE_None || !GDALInvGeoTransform(gt, inv))
    throw InputError(InputProblem::UnsupportedFormat, path, "",
                     "the raster is not georeferenced (no geotransform)");
  const int width = ds->GetRasterXSize(), height = ds->GetRasterYSize();
  DemSummary s;
  s.driver = ds->GetDriver() ? ds->GetDriver()->GetDescription() : "";
  s.raster_columns = width;
  s.raster_rows = height;

  // City (input coordinates) -> raster CRS. Without a CRS on either side the raster is taken to
  // be in the city's own coordinates.
  OGRSpatialReference city_srs;
  const bool city_known = city_crs(frame, city_srs);
  std::unique_ptr<OGRSpatialReference> dem_srs;
  if (const OGRSpatialReference* r = ds->GetSpatialRef()) {
    dem_srs.reset(r->Clone());
    dem_srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    s.crs = crs_name(*dem_srs);
  }
  std::vector<std::string> warnings;
  std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> to_dem;
  if (city_known && dem_srs) {
    if (!city_srs.IsSame(dem_srs.get())) {
      to_dem.reset(OGRCreateCoordinateTransformation(&city_srs, dem_srs.get()));
      if (!to_dem)
        throw InputError(InputProblem::UnknownCrs, path, "",
                         "cannot transform the city's " + crs_name(city_srs) +
                             " into the raster's " + s.crs + QuietGdal::last());
    }
  } else {
    if (!dem_srs) s.crs = "(none)";
    warnings.push_back(
        path + ": " +
        (dem_srs ? "the city names no reference system" : "the raster names no reference system") +
        ": its coordinates are taken as the city's");
  }

  const LocalFrameMapping mapping(frame);
  // Local point -> raster pixel coordinates (column, row; pixel centres at +0.5).
  auto to_pixel = [&](std::vector<double>& x, std::vector<double>& y, std::vector<int>& ok) {
    ok.assign(x.size(), 1);
    for (std::size_t k = 0; k < x.size(); ++k) {
      const Vec3 in = mapping.to_input(x[k], y[k], 0);
      x[k] = in.x, y[k] = in.y;
    }
    if (to_dem && !x.empty()) to_dem->Transform(x.size(), x.data(), y.data(), nullptr, ok.data());
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double px = inv[0] + inv[1] * x[k] + inv[2] * y[k];
      const double py = inv[3] + inv[4] * x[k] + inv[5] * y[k];
      x[k] = px, y[k] = py;
      if (!std::isfinite(px) || !std::isfinite(py)) ok[k] = 0;
    }
  };

  // The raster's pixel in metres, at the middle of the area: one local metre east and north
  // move the pixel coordinates by the Jacobian J; one pixel step is J^-1 applied to it.
  {
    const Vec2 c{0.5 * (area.min.x + area.max.x), 0.5 * (area.min.y + area.max.y)};
    std::vector<double> x{c.x, c.x + 1, c.x}, y{c.y, c.y, c.y + 1};
    std::vector<int> ok;
    to_pixel(x, y, ok);
    const double a = x[1] - x[0], b = x[2] - x[0], cc = y[1] - y[0], d = y[2] - y[0];
    const double det = a * d - b * cc;
    if (!(ok[0] && ok[1] && ok[2]) || !std::isfinite(det) || std::abs(det) < 1e-30)
      throw InputError(InputProblem::UnknownCrs, path, "",
                       "the city's coordinates cannot be placed on the raster" + QuietGdal::last());
    s.pixel_x = std::hypot(d / det, -cc / det);  // J^-1 (1, 0)
    s.pixel_y = std::hypot(-b / det, a / det);   // J^-1 (0, 1)
  }
  const double w = area.max.x - area.min.x, h = area.max.y - area.min.y;
  double spacing = std::max(kMinSpacing, 0.5 * std::min(s.pixel_x, s.pixel_y));
  const double nodes = (w / spacing + 1) * (h / spacing + 1);
  if (nodes > kMaxNodes) spacing *= std::sqrt(nodes / kMaxNodes);
  const int cols = int(std::ceil(w / spacing)) + 1, rows = int(std::ceil(h / spacing)) + 1;
  s.spacing = spacing, s.columns = cols, s.rows = rows;

  const std::size_t n = std::size_t(cols) * rows;
  std::vector<double> px(n), py(n);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      px[std::size_t(j) * cols + i] = area.min.x + i * spacing;
      py[std::size_t(j) * cols + i] = area.min.y + j * spacing;
    }
  std::vector<int> ok;
  to_pixel(px, py, ok);

  // The window of the raster the nodes fall on (with the neighbours bilinear needs).
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (std::size_t k = 0; k < n; ++k)
    if (ok[k])
      lo_x = std::min(lo_x, px[k]), hi_x = std::max(hi_x, px[k]), lo_y = std::min(lo_y, py[k]),
      hi_y = std::max(hi_y, py[k]);
  const int x0 = std::max(0, int(std::floor(lo_x - 1))),
            y0 = std::max(0, int(std::floor(lo_y - 1)));
  const int x1 = std::min(width, int(std::ceil(hi_x + 1))),
            y1 = std::min(height, int(std::ceil(hi_y + 1)));
  if (!(lo_x <= hi_x) || x0 >= x1 || y0 >= y1) {
    char what[200];
    std::snprintf(what, sizeof what,
                  "the raster (%s, %d x %d pixels) covers none of the city: wrong tile or "
                  "reference system?",
                  s.crs.c_str(), width, height);
    throw InputError(InputProblem::UnknownCrs, path, "", what);
  }
  const int ww = x1 - x0, wh = y1 - y0;
  const int f = std::max(1, int(std::ceil(std::sqrt(double(ww) * wh / kMaxPixels))));
  const int bw = std::max(1, ww / f), bh = std::max(1, wh / f);
  std::vector<double> raster(std::size_t(bw) * bh);
  GDALRasterBand* band = ds->GetRasterBand(1);
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.eResampleAlg = f > 1 ? GRIORA_Average : GRIORA_NearestNeighbour;
  if (band->RasterIO(GF_Read, x0, y0, ww, wh, raster.data(), bw, bh, GDT_Float64, 0, 0, &extra) !=
      CE_None)
    throw InputError(InputProblem::Unreadable, path, "", "read failed" + QuietGdal::last());
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  auto usable = [&](double v) { return std::isfinite(v) && !(has_nodata && v == nodata); };
  // Window pixels per buffer pixel, along each axis.
  const double sx = double(ww) / bw, sy = double(wh) / bh;

  // Bilinear between the centres of the four pixels around each node, over the usable ones.
  std::vector<double> z(n, 0.0);
  std::vector<char> known(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (!ok[k]) continue;
    const double u = (px[k] - x0) / sx - 0.5, v = (py[k] - y0) / sy - 0.5;
    if (u < -0.5 || v < -0.5 || u > bw - 0.5 || v > bh - 0.5) continue;  // off the raster
    const double uc = std::clamp(u, 0.0, double(bw - 1)), vc = std::clamp(v, 0.0, double(bh - 1));
    const int i0 = std::min(int(uc), bw - 1), j0 = std::min(int(vc), bh - 1);
    const int i1 = std::min(i0 + 1, bw - 1), j1 = std::min(j0 + 1, bh - 1);
    const double fu = uc - i0, fv = vc - j0;
    const double wgt[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
    const double val[4] = {raster[std::size_t(j0) * bw + i0], raster[std::size_t(j0) * bw + i1],
                           raster[std::size_t(j1) * bw + i0], raster[std::size_t(j1) * bw + i1]};
    double sum = 0, weight = 0;
    for (int q = 0; q < 4; ++q)
      if (usable(val[q])) sum += wgt[q] * val[q], weight += wgt[q];
    if (weight > 1e-9) z[k] = sum / weight, known[k] = 1;
  }
  if (std::find(known.begin(), known.end(), 1) == known.end())
    throw InputError(InputProblem::UnknownCrs, path, "",
                     "the raster holds no height anywhere under the city (all no-data)");
  s.filled = fill_unknown(z, known, cols, rows);
  if (s.filled > n / 10) {
    char what[160];
    std::snprintf(what, sizeof what,
                  ": %.0f%% of the ground around the city is off the raster or no-data, and "
                  "was filled from its edge",
                  100.0 * double(s.filled) / double(n));
    warnings.push_back(path + what);
  }

  Terrain t;
  t.triangles.reserve(2 * std::size_t(cols - 1) * (rows - 1));
  auto node = [&](int i, int j) {
    return Vec3{area.min.x + i * spacing, area.min.y + j * spacing, z[std::size_t(j) * cols + i]};
  };
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      t.triangles.push_back({{node(i, j), node(i + 1, j), node(i + 1, j + 1)}});
      t.triangles.push_back({{node(i, j), node(i + 1, j + 1), node(i, j + 1)}});
    }
  const auto [zlo, zhi] = std::minmax_element(z.begin(), z.end());
  s.zmin = *zlo, s.zmax = *zhi;
  s.warnings = std::move(warnings);
  if (summary) *summary = std::move(s);
  return t;
}

}  // namespace urbanpvs::geometry
