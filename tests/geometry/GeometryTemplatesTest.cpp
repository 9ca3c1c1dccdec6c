// SPDX-License-Identifier: GPL-3.0-or-later
// CityJSON geometry templates: a building whose geometry is a GeometryInstance is read as the
// template placed by its matrix at its reference vertex; a broken instance is refused, naming
// the object. The expected boxes are worked out here from the matrix.
#include <gtest/gtest.h>

#include <string>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace {

using namespace urbanpvs::geometry;

// A 10 x 10 x 12 m box as the template; "house" is an ordinary 10 x 10 x 15 m box at the
// origin, "kiosk" an instance whose reference vertex lies at (30, 0, 0) m.
std::string city_with_instance(const std::string& instance) {
  return R"({"type": "CityJSON", "version": "2.0",
    "transform": {"scale": [0.001, 0.001, 0.001], "translate": [84000, 447000, 0]},
    "metadata": {"referenceSystem": "https://www.opengis.net/def/crs/EPSG/0/7415"},
    "geometry-templates": {"templates": [{"type": "Solid", "lod": "1", "boundaries":
        [[[[0, 3, 2, 1]], [[4, 5, 6, 7]], [[0, 1, 5, 4]], [[1, 2, 6, 5]], [[2, 3, 7, 6]],
          [[3, 0, 4, 7]]]]}],
      "vertices-templates": [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0],
                             [0, 0, 12], [10, 0, 12], [10, 10, 12], [0, 10, 12]]},
    "CityObjects": {
      "house": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": "1",
        "boundaries": [[[0, 3, 2, 1]], [[4, 5, 6, 7]], [[0, 1, 5, 4]], [[1, 2, 6, 5]],
                       [[2, 3, 7, 6]], [[3, 0, 4, 7]]]}]},
      "kiosk": {"type": "Building", "geometry": [)" +
         instance + R"(]}},
    "vertices": [[0, 0, 0], [10000, 0, 0], [10000, 10000, 0], [0, 10000, 0], [0, 0, 15000],
                 [10000, 0, 15000], [10000, 10000, 15000], [0, 10000, 15000], [30000, 0, 0]]})";
}

TEST(GeometryTemplates, AnInstanceIsItsTemplatePlacedByItsMatrix) {
  // x' = -y + 5, y' = 2x, z' = z (a quarter turn, stretched twice along y'): the template's
  // 10 x 10 m footprint covers x in [-5, 5] and y in [0, 20] about the reference vertex.
  const City city = read_city_text(
      city_with_instance(R"({"type": "GeometryInstance", "template": 0, "boundaries": [8],
        "transformationMatrix": [0, -1, 0, 5, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]})"),
      "instance.city.json");
  ASSERT_EQ(city.objects.size(), 2u);
  const CityObject& kiosk = city.objects[1];
  EXPECT_EQ(kiosk.source_id, "kiosk");
  EXPECT_TRUE(kiosk.occludes);
  ASSERT_EQ(kiosk.occluders.size(), 1u);
  EXPECT_NEAR(area(kiosk.occluders[0].footprint), 200.0, 1e-6);
  EXPECT_NEAR(kiosk.occluders[0].top_z - kiosk.occluders[0].ground_z, 12.0, 1e-9);
  EXPECT_NEAR(kiosk.bbox.xy.min.x, 25.0, 1e-9);  // local frame: origin at (84000, 447000)
  EXPECT_NEAR(kiosk.bbox.xy.max.x, 35.0, 1e-9);
  EXPECT_NEAR(kiosk.bbox.xy.min.y, 0.0, 1e-9);
  EXPECT_NEAR(kiosk.bbox.xy.max.y, 20.0, 1e-9);
  EXPECT_FALSE(kiosk.surfaces.empty()) << "the validator's ground truth needs its surfaces";
}

TEST(GeometryTemplates, ABrokenInstanceIsRefusedNamingItsObject) {
  for (const auto& [instance, message] :
       {std::pair<std::string, std::string>{
            R"({"type": "GeometryInstance", "template": 3, "boundaries": [8]})",
            "kiosk: unexpected structure: GeometryInstance: \"template\" is no index into the "
            "templates"},
        {R"({"type": "GeometryInstance", "template": 0, "boundaries": [99]})",
         "kiosk: unexpected structure: GeometryInstance: \"boundaries\" must hold the index of "
         "its reference vertex"},
        {R"({"type": "GeometryInstance", "template": 0, "boundaries": [8],
             "transformationMatrix": [1, 0, 0]})",
         "kiosk: unexpected structure: GeometryInstance: transformationMatrix is no 16 numbers"}}) {
    try {
      (void)read_city_text(city_with_instance(instance), "broken.city.json");
      ADD_FAILURE() << "read: " << instance;
    } catch (const InputError& e) {
      EXPECT_EQ(e.problem(), InputProblem::BadStructure);
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
    // The same instance on a tree (no object of the city) costs nothing.
    std::string tree = city_with_instance(instance);
    const std::string building = R"("kiosk": {"type": "Building")";
    tree.replace(tree.find(building), building.size(),
                 R"("kiosk": {"type": "SolitaryVegetationObject")");
    EXPECT_EQ(read_city_text(tree, "tree.city.json").objects.size(), 1u) << instance;
  }
}

TEST(GeometryTemplates, ManyInstancesOfOneReferenceVertexEachInItsPlace) {
  // Twelve kiosks at the same reference vertex, moved 20 m apart by their matrices: placing
  // each appends the template's vertices to the array that holds the reference vertex, so the
  // reference must be read before the array grows (the CityJSON conformance corpus's
  // geometry_templates_reuse crashed the reader when it was read after).
  std::string objects;
  for (int k = 0; k < 12; ++k) {
    if (k > 0) objects += ",";
    objects += "\"kiosk" + std::to_string(k) +
               R"(": {"type": "Building", "geometry": [{"type": "GeometryInstance",
                 "template": 0, "boundaries": [1], "transformationMatrix":
                 [1, 0, 0, )" +
               std::to_string(20 * k) + R"(, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]})";
  }
  const std::string text = R"({"type": "CityJSON", "version": "2.0",
    "transform": {"scale": [0.01, 0.01, 0.01], "translate": [84000, 447000, 0]},
    "geometry-templates": {"templates": [{"type": "Solid", "lod": "1", "boundaries":
        [[[[0, 3, 2, 1]], [[4, 5, 6, 7]], [[0, 1, 5, 4]], [[1, 2, 6, 5]], [[2, 3, 7, 6]],
          [[3, 0, 4, 7]]]]}],
      "vertices-templates": [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0],
                             [0, 0, 12], [10, 0, 12], [10, 10, 12], [0, 10, 12]]},
    "CityObjects": {)" + objects +
                           R"(},
    "vertices": [[0, 0, 0], [500, 700, 0]]})";
  const City city = read_city_text(text, "kiosks.city.json");
  ASSERT_EQ(city.objects.size(), 12u);
  for (std::size_t k = 0; k < 12; ++k) {
    const CityObject& kiosk = city.objects[k];
    EXPECT_EQ(kiosk.source_id, "kiosk" + std::to_string(k));
    // The reference vertex lies at (5, 7) m from the translate; the local frame's origin is
    // the first kiosk's corner.
    EXPECT_NEAR(kiosk.bbox.xy.min.x - city.objects[0].bbox.xy.min.x, 20.0 * k, 1e-9);
    EXPECT_NEAR(kiosk.bbox.xy.max.x - kiosk.bbox.xy.min.x, 10.0, 1e-9);
    EXPECT_NEAR(kiosk.bbox.xy.min.y, city.objects[0].bbox.xy.min.y, 1e-9);
    EXPECT_NEAR(kiosk.bbox.zmax - kiosk.bbox.zmin, 12.0, 1e-9);
  }
}

}  // namespace
