// SPDX-License-Identifier: GPL-3.0-or-later
// The whole bake against the independent ray-cast ground truth (urbanpvs-validate's core): zero
// misses on generated cities with flat and LoD2 roofs, and a deliberately broken bake (occluders
// not shrunk) must be caught.
#include <gtest/gtest.h>

#include <filesystem>

#include "urbanpvs/cities/city_generator.hpp"
#include "urbanpvs/cities/cityjson_writer.hpp"
#include "urbanpvs/geometry/CityReader.hpp"
#include "urbanpvs/preprocess/CityBake.hpp"
#include "urbanpvs/runtime/pvs_file.hpp"
#include "urbanpvs/validate/Validator.hpp"

namespace urbanpvs {
namespace {

geometry::City generated(std::uint64_t seed, cities::RoofMode roofs) {
  cities::CityParams p;
  p.size_km2 = 0.1;
  p.seed = seed;
  p.roofs = roofs;
  return geometry::read_city_text(cities::cityJsonText(cities::generateCity(p)), "gen.city.json");
}

// Cells only in a 120 m square in the middle of the city, so the test stays fast; the cull
// maps still cover the whole city.
preprocess::BakeOptions small_bake(const geometry::City& city, double eps, double pixel,
                                   double half = 60) {
  preprocess::BakeOptions o;
  o.cells.epsilon = eps;
  o.cells.max_cell_edge = 25;
  o.pixel = pixel;
  const geometry::Box2 b = city.bounds().xy;
  const geometry::Vec2 c{0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y)};
  o.cells.region = {geometry::Polygon{{{c.x - half, c.y - half},
                                       {c.x + half, c.y - half},
                                       {c.x + half, c.y + half},
                                       {c.x - half, c.y + half}},
                                      {}}};
  return o;
}

validate::ValidationReport bake_and_validate(const geometry::City& city,
                                             const preprocess::BakeOptions& options,
                                             std::size_t viewpoints) {
  const runtime::PvsBake bake = preprocess::bake_city(city, options);
  runtime::PvsFile file;
  EXPECT_EQ(runtime::PvsFile::open_owned(runtime::encode(bake), file), runtime::Status::kOk);
  validate::ValidationOptions v;
  v.viewpoints = viewpoints;
  v.tightness_viewpoints = 100;
  const validate::ValidationReport r = validate::validate(city, file, v);
  for (std::size_t i = 0; i < r.misses.size() && i < 5; ++i)
    ADD_FAILURE() << "miss: cell " << r.misses[i].cell << " viewpoint (" << r.misses[i].viewpoint.x
                  << ", " << r.misses[i].viewpoint.y << ", " << r.misses[i].viewpoint.z << ") sees "
                  << r.misses[i].object_id;
  std::printf("cells %zu viewpoints %zu rays %zu misses %zu tightness %.3f\n", bake.cells.size(),
              r.viewpoints, r.rays, r.misses.size(), r.tightness());
  return r;
}

TEST(Validate, NoMissesOnFlatCity) {
  const geometry::City city = generated(3, cities::RoofMode::Flat);
  const auto r = bake_and_validate(city, small_bake(city, 1.0, 1.39), 2000);
  EXPECT_TRUE(r.misses.empty());
  EXPECT_GT(r.tightness(), 0.0);
}

TEST(Validate, NoMissesOnLod2City) {
  const geometry::City city = generated(8, cities::RoofMode::Lod2);
  const auto r = bake_and_validate(city, small_bake(city, 1.0, 1.39), 2000);
  EXPECT_TRUE(r.misses.empty());
}

// Delft: buildings whose bases float up to ~0.5 m above the ground interpolated between them
// and cells whose ground slopes; viewpoints down to the ground. Cells in a 50 m square in the
// middle (the dense old town gives small cells); the maps still cover the whole extract. The
// whole extract (10,000 viewpoints, 0 misses) is in issue 4's note.
TEST(Validate, NoMissesOnDelft) {
  const std::filesystem::path path =
      std::filesystem::path(URBANPVS_SHARED_CITIES) / "delft.city.json";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const geometry::City city = geometry::read_city({path.string()}, {});
  const auto r = bake_and_validate(city, small_bake(city, 1.0, 1.39, 25), 2000);
  EXPECT_TRUE(r.misses.empty());
}

TEST(Validate, CatchesUnshrunkOccluders) {
  const geometry::City city = generated(3, cities::RoofMode::Flat);
  preprocess::BakeOptions broken = small_bake(city, 4.0, 5.5);
  broken.shrink_override = 0;  // occluders as large as the buildings: not conservative
  const runtime::PvsBake bake = preprocess::bake_city(city, broken);
  runtime::PvsFile file;
  ASSERT_EQ(runtime::PvsFile::open_owned(runtime::encode(bake), file), runtime::Status::kOk);
  validate::ValidationOptions v;
  v.viewpoints = 3000;
  v.tightness_viewpoints = 0;
  EXPECT_FALSE(validate::validate(city, file, v).misses.empty());
}

}  // namespace
}  // namespace urbanpvs
