// SPDX-License-Identifier: GPL-3.0-or-later
// Writes a CityJSON file's vertices in another reference system, for benchmarks/
// reprojected_cities.sh: a real city in lon/lat, Web Mercator or a state plane in feet, to bake
// and validate as users bring such files. PROJ (through GDAL) transforms x, y; z is converted
// into the target's linear unit (feet for a state plane), as such files give their heights.
//   cityjson_reproject IN.city.json OUT.city.json FROM_EPSG TO_EPSG
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::ordered_json;

struct TransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const {
    OGRCoordinateTransformation::DestroyCT(t);
  }
};

OGRSpatialReference system_of(const char* code) {
  OGRSpatialReference s;
  if (s.importFromEPSG(std::atoi(code)) != OGRERR_NONE)
    throw std::runtime_error(std::string("unknown EPSG code ") + code);
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: cityjson_reproject IN.city.json OUT.city.json FROM_EPSG TO_EPSG\n";
    return 2;
  }
  try {
    std::ifstream in(argv[1]);
    Json doc = Json::parse(in);
    const OGRSpatialReference from = system_of(argv[3]), to = system_of(argv[4]);
    const std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> transform(
        OGRCreateCoordinateTransformation(&from, &to));
    if (!transform) throw std::runtime_error("PROJ cannot transform between these systems");
    std::array<double, 3> scale{1, 1, 1}, translate{0, 0, 0};
    if (doc.contains("transform"))
      for (std::size_t i = 0; i < 3; ++i) {
        scale[i] = doc["transform"]["scale"][i].get<double>();
        translate[i] = doc["transform"]["translate"][i].get<double>();
      }
    const double z_unit = to.IsProjected() ? to.GetLinearUnits() : 1.0;
    std::vector<double> x, y, z;
    for (const Json& v : doc["vertices"]) {
      x.push_back(v[0].get<double>() * scale[0] + translate[0]);
      y.push_back(v[1].get<double>() * scale[1] + translate[1]);
      z.push_back((v[2].get<double>() * scale[2] + translate[2]) / z_unit);
    }
    std::vector<int> ok(x.size());
    transform->Transform(x.size(), x.data(), y.data(), nullptr, ok.data());
    if (std::find(ok.begin(), ok.end(), 0) != ok.end())
      throw std::runtime_error("a vertex could not be transformed");
    // Integer vertices again, a tenth of a millimetre or finer: 1e-9 degrees, 1e-4 units.
    const double q = to.IsGeographic() ? 1e-9 : 1e-4;
    const double x0 = *std::min_element(x.begin(), x.end());
    const double y0 = *std::min_element(y.begin(), y.end());
    for (std::size_t k = 0; k < x.size(); ++k)
      doc["vertices"][k] = Json::array({std::llround((x[k] - x0) / q),
                                        std::llround((y[k] - y0) / q), std::llround(z[k] / 1e-4)});
    doc["transform"] = Json{{"scale", {q, q, 1e-4}}, {"translate", {x0, y0, 0.0}}};
    doc["metadata"]["referenceSystem"] =
        std::string("https://www.opengis.net/def/crs/EPSG/0/") + argv[4];
    doc["metadata"].erase("geographicalExtent");
    std::ofstream(argv[2]) << doc.dump();
  } catch (const std::exception& e) {
    std::cerr << "cityjson_reproject: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
