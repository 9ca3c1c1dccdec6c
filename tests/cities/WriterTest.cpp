// CityJSON and GeoJSON structure, and the bundled sample city.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "CityTestSupport.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/cities/GeoJsonWriter.hpp"

using namespace citytest;
using nlohmann::json;

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void checkCityJson(const City& c, const json& doc) {
  ASSERT_EQ(doc.at("type"), "CityJSON");
  ASSERT_EQ(doc.at("version"), "2.0");
  const json& tr = doc.at("transform");
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(tr.at("scale")[k].get<double>(), 0.001);
  EXPECT_DOUBLE_EQ(tr.at("translate")[0].get<double>(), c.params.origin_x);
  EXPECT_DOUBLE_EQ(tr.at("translate")[1].get<double>(), c.params.origin_y);
  EXPECT_EQ(doc.at("metadata").at("referenceSystem"),
            "https://www.opengis.net/def/crs/EPSG/0/31256");
  EXPECT_EQ(doc.at("metadata").at("geographicalExtent").size(), 6u);

  const json& vertices = doc.at("vertices");
  ASSERT_FALSE(vertices.empty());
  for (const json& v : vertices) {
    ASSERT_EQ(v.size(), 3u);
    for (const json& x : v) ASSERT_TRUE(x.is_number_integer());
  }
  const json& objects = doc.at("CityObjects");
  EXPECT_EQ(objects.size(), urbanpvs::cities::cityObjectCount(c));
  const std::string lod = c.params.roofs == RoofMode::Lod2 ? "2.2" : "1.2";
  std::set<std::string> semantic_types;
  for (const auto& b : c.buildings) {
    const json& o = objects.at(b.id);
    EXPECT_EQ(o.at("type"), "Building");
    EXPECT_TRUE(o.at("attributes").at("measuredHeight").is_number());
    EXPECT_NEAR(o.at("attributes").at("measuredHeight").get<double>(), b.ridge_height, 1e-9);
    std::vector<std::pair<const json*, const urbanpvs::cities::Solid*>> geoms;
    if (b.parts.empty()) {
      geoms.emplace_back(&o, &b.solid);
    } else {
      ASSERT_EQ(o.at("children").size(), b.parts.size());
      for (const auto& part : b.parts) {
        const json& po = objects.at(part.id);
        EXPECT_EQ(po.at("type"), "BuildingPart");
        EXPECT_EQ(po.at("parents")[0], b.id);
        geoms.emplace_back(&po, &part.solid);
      }
    }
    for (const auto& [obj, solid] : geoms) {
      const json& g = obj->at("geometry").at(0);
      EXPECT_EQ(g.at("type"), "Solid");
      EXPECT_EQ(g.at("lod"), lod);
      const json& shell = g.at("boundaries").at(0);
      ASSERT_EQ(shell.size(), solid->faces.size());
      const json& values = g.at("semantics").at("values").at(0);
      ASSERT_EQ(values.size(), shell.size());
      const json& surfaces = g.at("semantics").at("surfaces");
      for (const json& v : values)
        semantic_types.insert(surfaces.at(v.get<std::size_t>()).at("type"));
      for (const json& face : shell) {
        for (const json& ring : face) {
          for (const json& idx : ring) ASSERT_LT(idx.get<std::size_t>(), vertices.size());
        }
      }
    }
  }
  EXPECT_EQ(semantic_types, (std::set<std::string>{"GroundSurface", "WallSurface", "RoofSurface"}));
}

void checkGeoJson(const City& c, const json& doc) {
  ASSERT_EQ(doc.at("type"), "FeatureCollection");
  EXPECT_EQ(doc.at("crs").at("properties").at("name"), "urn:ogc:def:crs:EPSG::31256");
  std::size_t expected = 0;
  for (const auto& b : c.buildings) expected += b.parts.empty() ? 1 : b.parts.size();
  const json& features = doc.at("features");
  ASSERT_EQ(features.size(), expected);
  for (const json& f : features) {
    EXPECT_EQ(f.at("type"), "Feature");
    const json& props = f.at("properties");
    EXPECT_TRUE(props.at("id").is_string());
    EXPECT_TRUE(props.at("height").is_number());
    EXPECT_TRUE(props.at("building:levels").is_number_integer());
    EXPECT_GE(props.at("roof:height").get<double>(), 0.0);
    const json& geom = f.at("geometry");
    EXPECT_EQ(geom.at("type"), "Polygon");
    for (const json& ring : geom.at("coordinates")) {
      ASSERT_GE(ring.size(), 4u);
      EXPECT_EQ(ring.front(), ring.back());  // RFC 7946: closed rings
      // Same projected metres as the model: local + origin.
      EXPECT_GE(ring[0][1].get<double>(), c.params.origin_y);
    }
  }
}

}  // namespace

TEST(Writers, CityJsonFlatIsValid) {
  const City& c = oneKm2Flat();
  checkCityJson(c, json::parse(urbanpvs::cities::cityJsonText(c)));
}

TEST(Writers, CityJsonLod2IsValid) {
  const City& c = oneKm2Lod2();
  checkCityJson(c, json::parse(urbanpvs::cities::cityJsonText(c)));
}

TEST(Writers, GeoJsonIsValid) {
  for (const City* c : {&oneKm2Flat(), &oneKm2Lod2()}) {
    checkGeoJson(*c, json::parse(urbanpvs::cities::geoJsonText(*c)));
  }
}

TEST(Writers, VerticesAreTheModelsMillimetres) {
  const City& c = oneKm2Lod2();
  const json doc = json::parse(urbanpvs::cities::cityJsonText(c));
  const json& v = doc.at("vertices");
  std::size_t k = 0;
  for (const auto& b : c.buildings) {
    const auto check = [&](const urbanpvs::cities::Solid& s) {
      for (const auto& p : s.vertices) {
        ASSERT_LT(k, v.size());
        EXPECT_EQ(v[k][0].get<std::int64_t>(), mm(p.x));
        EXPECT_EQ(v[k][1].get<std::int64_t>(), mm(p.y));
        EXPECT_EQ(v[k][2].get<std::int64_t>(), mm(p.z));
        ++k;
      }
    };
    check(b.solid);
    for (const auto& part : b.parts) check(part.solid);
  }
  EXPECT_EQ(k, v.size());
}

// The bundled sample must be exactly what the generator writes for the documented parameters
// (cities/sample/README.md); regenerate with `cmake --build <dir> --target regenerate-sample`.
TEST(Writers, BundledSampleMatchesGenerator) {
  const City c = urbanpvs::cities::generateCity(urbanpvs::cities::sampleDistrictParams());
  const std::string dir = URBANPVS_CITIES_SAMPLE_DIR;
  const std::string cityjson = readFile(dir + "/district.city.json");
  const std::string geojson = readFile(dir + "/district.geojson");
  ASSERT_FALSE(cityjson.empty()) << "missing " << dir << "/district.city.json";
  ASSERT_FALSE(geojson.empty()) << "missing " << dir << "/district.geojson";
  EXPECT_TRUE(cityjson == urbanpvs::cities::cityJsonText(c))
      << "district.city.json drifted from the generator: run the regenerate-sample target";
  EXPECT_TRUE(geojson == urbanpvs::cities::geoJsonText(c))
      << "district.geojson drifted from the generator: run the regenerate-sample target";
  EXPECT_LT(cityjson.size(), 1'500'000u);
  EXPECT_LT(geojson.size(), 1'500'000u);
}
