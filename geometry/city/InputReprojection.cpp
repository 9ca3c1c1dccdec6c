// SPDX-License-Identifier: GPL-3.0-or-later
// Input in a reference system whose coordinates are not metres as they stand: a projection in
// feet (the US state planes, e.g. New York's EPSG:2263), a Mercator (EPSG:3857: its "metres" are
// 1/cos(latitude) true metres), or degrees on a datum other than WGS84 (ETRS89, NAD83, JGD2011
// as Japan's PLATEAU models give them). Every stage works in metres (ε, the cells, the eye band,
// the PVS file's frame), so such input is transformed by PROJ (through GDAL) into WGS84 lon/lat,
// which the local east-north-up frame takes as it takes any geographic input. A city of a few
// kilometres keeps its shape to millimetres: the datum shift moves it as a whole.
#include "InputReprojection.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "GdalHandles.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

constexpr const char* kWgs84Name = "urn:ogc:def:crs:OGC:1.3:CRS84";

// The system a normalised name designates; false when GDAL does not know it. Never reads a
// file or the network: a CRS name in a city file is data, not an address to fetch.
bool system_of(const std::string& crs, OGRSpatialReference& s) {
  const QuietGdal quiet;
  OGRErr err = OGRERR_FAILURE;
  if (crs.rfind("EPSG:", 0) == 0) {
    const std::string digits = crs.substr(5);
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    err = s.importFromEPSG(std::stoi(digits));
  } else {
    err =
        s.SetFromUserInput(crs.c_str(), OGRSpatialReference::SET_FROM_USER_INPUT_LIMITATIONS_get());
  }
  if (err != OGRERR_NONE) return false;
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = east / longitude
  return true;
}

// A CityJSON or GeoJSON position: two or three numbers.
bool is_position(const Json& p) {
  if (!p.is_array() || p.size() < 2 || p.size() > 3) return false;
  for (const Json& v : p)
    if (!v.is_number()) return false;
  return true;
}

// The positions of a GeoJSON geometry's "coordinates" (nested arrays of any depth), in order.
void collect_positions(Json& node, std::vector<Json*>& out) {
  if (!node.is_array()) return;
  if (is_position(node)) {
    out.push_back(&node);
    return;
  }
  for (Json& child : node) collect_positions(child, out);
}

// The positions of a GeoJSON geometry, a GeometryCollection's members' included (the reader
// takes their polygons).
void geometry_positions(Json& geometry, std::vector<Json*>& out) {
  if (!geometry.is_object()) return;
  if (geometry.contains("coordinates")) collect_positions(geometry["coordinates"], out);
  if (geometry.contains("geometries") && geometry["geometries"].is_array())
    for (Json& member : geometry["geometries"]) geometry_positions(member, out);
}

// Transforms x, y in place; throws naming `file` and `what` where PROJ cannot.
void transform_all(Reprojection& r, std::vector<double>& x, std::vector<double>& y,
                   const std::string& file, const char* what) {
  if (x.empty()) return;
  std::vector<int> ok(x.size(), 0);
  {
    const QuietGdal quiet;
    r.to_wgs84->Transform(x.size(), x.data(), y.data(), nullptr, ok.data());
  }
  for (std::size_t k = 0; k < x.size(); ++k)
    if (!ok[k] || !std::isfinite(x[k]) || !std::isfinite(y[k])) {
      char msg[200];
      std::snprintf(msg, sizeof msg, "%s %zu cannot be transformed from %s to WGS84 lon/lat", what,
                    k, r.from.c_str());
      throw InputError(InputProblem::UnknownCrs, file, "", msg);
    }
}

}  // namespace

std::string identify_crs(const std::string& name) {
  // Swiss files name their systems by the datum alone: "CH1903" for the LV03 grid, "CH1903+"
  // for LV95 (PROJ would take the bare datum names for the geographic systems).
  if (name == "CH1903" || name == "CH1903 / LV03") return "EPSG:21781";
  if (name == "CH1903+" || name == "CH1903+ / LV95") return "EPSG:2056";
  // Only names and codes ("ESRI:102100", "urn:ogc:def:crs:ESRI::102100"), not definitions: a
  // city file's WKT or PROJ string would be a parser of GDAL's that this reader exposes to
  // untrusted input for no data set that needs it.
  if (name.size() > 200 || name.find_first_of("[{(+ ") != std::string::npos) return {};
  OGRSpatialReference s;
  return system_of(name, s) ? authority_code(s) : std::string();
}

bool is_metric_projection(const OGRSpatialReference& s) {
  return s.IsProjected() && std::abs(s.GetLinearUnits() - 1) < 1e-9 && !is_mercator(s);
}

std::string authority_code(const OGRSpatialReference& s) {
  const char* authority = s.GetAuthorityName(nullptr);
  const char* code = s.GetAuthorityCode(nullptr);
  const bool own = authority != nullptr && code != nullptr;
  if (own && std::string(authority) == "EPSG") return std::string("EPSG:") + code;
  const QuietGdal quiet;
  if (OGRSpatialReference* match = s.FindBestMatch(90, "EPSG", nullptr)) {
    const char* a = match->GetAuthorityName(nullptr);
    const char* c = match->GetAuthorityCode(nullptr);
    std::string found = a != nullptr && c != nullptr ? std::string(a) + ":" + c : std::string();
    match->Release();
    if (!found.empty()) return found;
  }
  return own ? std::string(authority) + ":" + code : std::string();
}

Reprojection reprojection_from(const OGRSpatialReference& s, const std::string& name,
                               const std::string& file, const std::string& object) {
  if (!s.IsProjected() && !s.IsGeographic())
    throw InputError(InputProblem::UnknownCrs, file, object,
                     name +
                         " is neither a map projection nor longitude and latitude: reproject "
                         "the input to a projected system in metres or to WGS84 lon/lat");
  Reprojection r;
  const char* unit = nullptr;
  const double metres = s.IsProjected() ? s.GetLinearUnits(&unit) : 1;
  r.from = name + (s.IsGeographic() ? " (degrees)"
                   : is_mercator(s) ? " (Mercator)"
                                    : " (in " + std::string(unit != nullptr ? unit : "?") + ")");
  // A projection in feet gives its heights in feet too (the state planes' own vertical data
  // does, and a file names one system for all three axes).
  r.z_to_metres = metres;
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const QuietGdal quiet;
  r.to_wgs84.reset(OGRCreateCoordinateTransformation(&s, &wgs84));
  if (!r.to_wgs84)
    throw InputError(InputProblem::UnknownCrs, file, object,
                     "cannot transform " + r.from + " to WGS84 lon/lat" + QuietGdal::last());
  return r;
}

std::optional<Reprojection> reprojection_for(const std::string& crs, const std::string& file) {
  if (crs.empty() || is_geographic_crs(crs)) return std::nullopt;
  OGRSpatialReference s;
  // A system PROJ does not know is taken as metres, as the file says nothing else.
  if (!system_of(crs, s) || is_metric_projection(s)) return std::nullopt;
  return reprojection_from(s, crs, file, "");
}

bool latitude_first(const std::string& crs) {
  if (crs == "EPSG:4326" || crs == "EPSG:4979") return true;
  OGRSpatialReference s;
  return crs.rfind("EPSG:", 0) == 0 && system_of(crs, s) && s.IsGeographic() &&
         s.EPSGTreatsAsLatLong();
}

void reproject_cityjson(Json& doc, Reprojection& r, const std::string& file) {
  if (!doc.contains("vertices") || !doc["vertices"].is_array()) return;  // the reader says so
  Json& vertices = doc["vertices"];
  std::array<double, 3> scale{1, 1, 1}, translate{0, 0, 0};
  if (doc.contains("transform")) {  // the scan has read it: three numbers each
    const Json& t = doc["transform"];
    for (std::size_t i = 0; i < 3; ++i) {
      scale[i] = json_number(t["scale"][i], file, "transform", "transform.scale");
      translate[i] = json_number(t["translate"][i], file, "transform", "transform.translate");
    }
  }
  std::vector<double> x, y, z;
  x.reserve(vertices.size()), y.reserve(vertices.size()), z.reserve(vertices.size());
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Json& v = vertices[k];
    if (!v.is_array() || v.size() != 3)
      throw InputError(InputProblem::BadStructure, file, "vertices",
                       "vertex " + std::to_string(k) + " is not three numbers");
    x.push_back(json_number(v[0], file, "vertices", "vertex coordinate") * scale[0] + translate[0]);
    y.push_back(json_number(v[1], file, "vertices", "vertex coordinate") * scale[1] + translate[1]);
    z.push_back(json_number(v[2], file, "vertices", "vertex coordinate") * scale[2] + translate[2]);
  }
  transform_all(r, x, y, file, "vertex");
  // Plain coordinates from here on (an identity transform, which CityJSON 1.1 and 2.0 require):
  // degrees would lose their metres to the file's integer grid.
  for (std::size_t k = 0; k < x.size(); ++k)
    vertices[k] = Json::array({x[k], y[k], z[k] * r.z_to_metres});
  doc["transform"] = Json{{"scale", {1.0, 1.0, 1.0}}, {"translate", {0.0, 0.0, 0.0}}};
  doc["metadata"]["referenceSystem"] = kWgs84Name;
}

void reproject_geojson(Json& doc, Reprojection& r, const std::string& file) {
  std::vector<Json*> positions;
  auto feature_positions = [&](Json& feature) {
    if (feature.is_object() && feature.contains("geometry"))
      geometry_positions(feature["geometry"], positions);
  };
  if (doc.contains("features") && doc["features"].is_array())
    for (Json& f : doc["features"]) feature_positions(f);
  else
    feature_positions(doc);  // a single Feature
  std::vector<double> x, y;
  x.reserve(positions.size()), y.reserve(positions.size());
  for (const Json* p : positions) {
    x.push_back((*p)[0].get<double>());
    y.push_back((*p)[1].get<double>());
  }
  transform_all(r, x, y, file, "position");
  for (std::size_t k = 0; k < positions.size(); ++k) {
    Json& p = *positions[k];
    p[0] = x[k], p[1] = y[k];  // GeoJSON heights are properties in metres (parse_length)
  }
  doc["crs"] = Json{{"type", "name"}, {"properties", {{"name", kWgs84Name}}}};
}

}  // namespace urbanpvs::geometry::detail
