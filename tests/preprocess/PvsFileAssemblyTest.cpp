// SPDX-License-Identifier: GPL-3.0-or-later
// The two ways to bake, bake_city (one call, one thread) and urbanpvs-preprocess (parallel,
// journalled), assemble their files in one place (BakeScene::pvs_file): for the same city and
// settings they store the same objects, cells and PVSs, and the command's properties are
// bake_city's with the command's own provenance around them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/bake/CityBake.hpp"
#include "urbanpvs/preprocess/bake/CompactPvsStore.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace fs = std::filesystem;
using namespace urbanpvs;

namespace {

const std::string kCity = std::string(URBANPVS_SAMPLE_DIR) + "/district.city.json";

// Cells in a 60 m square in the middle of the bundled district: a bake of a second or two.
preprocess::BakeOptions small_bake(const geometry::City& city) {
  geometry::Box2 all;
  for (const geometry::CityObject& o : city.objects) all.extend(o.bbox.xy);
  const geometry::Vec2 c{(all.min.x + all.max.x) / 2, (all.min.y + all.max.y) / 2};
  preprocess::BakeOptions o;
  o.cells.max_cell_edge = 30;
  o.cells.region = {
      {{{c.x - 30, c.y - 30}, {c.x + 30, c.y - 30}, {c.x + 30, c.y + 30}, {c.x - 30, c.y + 30}},
       {}}};
  return o;
}

std::vector<std::pair<std::string, std::string>> properties_of(const runtime::PvsFile& f) {
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t i = 0; i < f.property_count(); ++i) {
    std::string_view key, value;
    EXPECT_EQ(f.property(i, key, value), runtime::Status::kOk);
    out.emplace_back(std::string(key), std::string(value));
  }
  return out;
}

}  // namespace

TEST(PvsFileAssembly, BakeCityAndThePreprocessCommandStoreTheSameFile) {
  const geometry::City city = geometry::read_city({kCity});
  const preprocess::BakeOptions options = small_bake(city);
  const runtime::PvsBake direct = preprocess::bake_city(city, options);

  const fs::path out =
      fs::temp_directory_path() / ("urbanpvs_assembly_" + std::to_string(::getpid()) + ".pvs");
  preprocess::PreprocessRequest request;
  request.inputs = {kCity};
  request.output = out.string();
  request.bake = options;
  request.threads = 2;
  request.quiet = true;
  ASSERT_EQ(preprocess::run_preprocess(request), 0);
  runtime::PvsFile file;
  ASSERT_EQ(runtime::PvsFile::open_file(out.c_str(), file), runtime::Status::kOk);
  fs::remove(out);

  ASSERT_EQ(file.cell_count(), direct.cells.size());
  ASSERT_GT(file.cell_count(), 10u);
  ASSERT_EQ(file.object_count(), direct.objects.size());
  runtime::PvsDecoder decoder(file);
  for (std::uint32_t c = 0; c < file.cell_count(); ++c) {
    ASSERT_EQ(decoder.decode(c), runtime::Status::kOk);
    const std::vector<std::uint32_t> pvs(decoder.view().begin(), decoder.view().end());
    std::vector<std::uint32_t> expected = direct.cells[c].pvs;
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(pvs, expected) << "cell " << c;
  }
  // The command's properties: its version, then bake_city's own, in their order, then the
  // reading options, region and inputs.
  const auto stored = properties_of(file);
  ASSERT_GE(stored.size(), direct.meta.properties.size() + 1);
  EXPECT_EQ(stored.front().first, "tool");
  for (std::size_t i = 0; i < direct.meta.properties.size(); ++i)
    EXPECT_EQ(stored[i + 1], direct.meta.properties[i]) << "property " << i;
  EXPECT_EQ(file.settings().epsilon_m, direct.meta.settings.epsilon_m);
  EXPECT_EQ(file.settings().max_cell_edge_m, 30.0);
}

// urbanpvs-preprocess hands its lists to the writer from the compact store: the file's bytes are
// those of the same lists as vectors, in both codings.
TEST(PvsFileAssembly, TheCompactStoreGivesTheBytesOfTheLists) {
  const geometry::City city = geometry::read_city({kCity});
  const preprocess::BakeOptions options = small_bake(city);
  const runtime::PvsBake direct = preprocess::bake_city(city, options);
  const preprocess::BakeScene scene(city, options);
  ASSERT_EQ(scene.cell_count(), direct.cells.size());
  preprocess::CompactPvsStore store(scene.cell_count(),
                                    static_cast<std::uint32_t>(city.objects.size()));
  std::vector<std::vector<std::uint32_t>> lists;
  for (std::uint32_t c = 0; c < scene.cell_count(); ++c) {
    std::vector<std::uint32_t> pvs = direct.cells[c].pvs;
    std::sort(pvs.begin(), pvs.end());
    store.store(c, pvs);
    lists.push_back(std::move(pvs));
  }
  const runtime::PvsBake from_store = scene.pvs_file(store, {{"k", "v"}}, 7);
  const runtime::PvsBake from_lists = scene.pvs_file(std::move(lists), {{"k", "v"}}, 7);
  for (runtime::PvsCoding coding : {runtime::PvsCoding::kExpGolomb, runtime::PvsCoding::kVarint}) {
    runtime::EncodeOptions o;
    o.pvs_coding = coding;
    const std::vector<std::byte> bytes = runtime::encode(from_store, o);
    EXPECT_EQ(bytes, runtime::encode(from_lists, o));
    EXPECT_GT(bytes.size(), 100u);
  }
}
