// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-explain's breakdown of the excess (ExcessBreakdown.hpp) on small generated cities:
// the causes account for exactly the excess the validator measures; the mechanism that a
// setting controls takes a larger share when the setting is coarser (ε for the epsilon share,
// the cell edge for the elsewhere-in-cell share); and a file whose PVS is not what its settings
// bake is refused rather than explained.
#include <gtest/gtest.h>

#include <stdexcept>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/explain/ExcessBreakdown.hpp"
#include "urbanpvs/explain/ExcessReport.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"
#include "urbanpvs/preprocess/bake/CityBake.hpp"

namespace urbanpvs {
namespace {

using explain::ExcessCause;

const geometry::City& city() {
  static const geometry::City c = [] {
    cities::CityParams p;
    p.size_km2 = 0.1;
    p.seed = 3;
    return geometry::read_city_text(cities::cityJsonText(cities::generateCity(p)), "gen.city.json");
  }();
  return c;
}

// Cells in a 140 m square in the middle of the city; the maps still cover all of it.
preprocess::BakeOptions bake_options(double epsilon, double max_cell_edge) {
  preprocess::BakeOptions o;
  o.cells.epsilon = epsilon;
  o.cells.max_cell_edge = max_cell_edge;
  o.pixel = preprocess::default_pixel(epsilon);
  const geometry::Box2 b = city().bounds().xy;
  const geometry::Vec2 c{0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y)};
  o.cells.region = {geometry::Polygon{
      {{c.x - 70, c.y - 70}, {c.x + 70, c.y - 70}, {c.x + 70, c.y + 70}, {c.x - 70, c.y + 70}},
      {}}};
  return o;
}

explain::ExplainOptions explain_options(std::size_t viewpoints = 60) {
  explain::ExplainOptions o;
  o.validation.viewpoints = o.validation.tightness_viewpoints = viewpoints;
  o.cell_viewpoints = 16;
  o.threads = 2;
  return o;
}

explain::ExcessBreakdown explained(const runtime::PvsBake& bake,
                                   const preprocess::BakeOptions& options,
                                   std::size_t viewpoints = 60) {
  runtime::PvsFile file;
  EXPECT_EQ(runtime::PvsFile::open_owned(runtime::encode(bake), file), runtime::Status::kOk);
  return explain::explain_excess(city(), file, options, explain_options(viewpoints));
}

double per_viewpoint(const explain::ExcessBreakdown& b, ExcessCause cause) {
  return static_cast<double>(b.counts[static_cast<std::size_t>(cause)]) /
         static_cast<double>(b.viewpoints.size());
}

TEST(Explain, TheCausesAccountForExactlyTheExcess) {
  const preprocess::BakeOptions options = bake_options(1, 18);
  const explain::ExcessBreakdown b = explained(preprocess::bake_city(city(), options), options);
  ASSERT_TRUE(b.validation.misses.empty());
  ASSERT_EQ(b.viewpoints.size(), 60u);
  EXPECT_GT(b.excess(), 0u);
  EXPECT_EQ(b.excess(), b.validation.pvs_total - b.validation.seen_total);
  std::size_t counted = 0, pvs = 0, seen = 0;
  for (const std::size_t n : b.counts) counted += n;
  for (const explain::ViewpointTally& v : b.viewpoints) pvs += v.pvs, seen += v.seen;
  EXPECT_EQ(counted, b.excess());
  EXPECT_EQ(pvs, b.validation.pvs_total);
  EXPECT_EQ(seen, b.validation.seen_total);
  // Each excess object once per viewpoint, in viewpoint order then object order.
  for (std::size_t i = 1; i < b.objects.size(); ++i) {
    const auto& a = b.objects[i - 1];
    const auto& c = b.objects[i];
    EXPECT_TRUE(a.viewpoint < c.viewpoint || (a.viewpoint == c.viewpoint && a.object < c.object));
  }
  // The CSV has a line per excess object and the table a row per cause.
  const std::string csv = explain::objects_csv(b, city());
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), b.excess() + 1);
  const std::string table = explain::breakdown_table(b);
  for (std::size_t c = 0; c < explain::kExcessCauses; ++c)
    EXPECT_NE(
        table.find(std::string("| ") + explain::cause_name(static_cast<ExcessCause>(c)) + " |"),
        std::string::npos);
  std::printf("%s", table.c_str());
}

TEST(Explain, ACoarserEpsilonLetsInMoreByEpsilon) {
  const preprocess::BakeOptions fine = bake_options(0.5, 18), coarse = bake_options(3, 18);
  const auto f = explained(preprocess::bake_city(city(), fine), fine);
  const auto c = explained(preprocess::bake_city(city(), coarse), coarse);
  std::printf("epsilon share per viewpoint: eps 0.5 %.2f, eps 3 %.2f\n",
              per_viewpoint(f, ExcessCause::Epsilon), per_viewpoint(c, ExcessCause::Epsilon));
  EXPECT_GT(per_viewpoint(c, ExcessCause::Epsilon), 0);
  EXPECT_GT(per_viewpoint(c, ExcessCause::Epsilon), 1.5 * per_viewpoint(f, ExcessCause::Epsilon));
}

TEST(Explain, LargerCellsLetInMoreFromElsewhereInTheCell) {
  const preprocess::BakeOptions small = bake_options(1, 9), large = bake_options(1, 40);
  const auto s = explained(preprocess::bake_city(city(), small), small);
  const auto l = explained(preprocess::bake_city(city(), large), large);
  std::printf("elsewhere-in-cell per viewpoint: edge 9 %.2f, edge 40 %.2f\n",
              per_viewpoint(s, ExcessCause::ElsewhereInCell),
              per_viewpoint(l, ExcessCause::ElsewhereInCell));
  EXPECT_GT(per_viewpoint(l, ExcessCause::ElsewhereInCell),
            1.5 * per_viewpoint(s, ExcessCause::ElsewhereInCell));
}

// A file that says its PVS is everything (conservative, but not what its settings bake) is not
// explained: its excess would be put down to the wrong causes.
TEST(Explain, AFileTheSettingsDoNotBakeIsRefused) {
  const preprocess::BakeOptions options = bake_options(1, 18);
  runtime::PvsBake bake = preprocess::bake_city(city(), options);
  for (runtime::CellRecord& c : bake.cells) {
    c.pvs.resize(city().objects.size());
    for (std::uint32_t o = 0; o < c.pvs.size(); ++o) c.pvs[o] = o;
  }
  try {
    explained(bake, options, 10);
    ADD_FAILURE() << "a PVS that the settings do not bake was explained";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("cell ", 0), 0u) << what;
    EXPECT_NE(what.find(": the file's PVS is not what its settings bake (another version of "
                        "urbanpvs-preprocess, or a changed file?)"),
              std::string::npos)
        << what;
  }
  // Another cell edge gives other cells: refused before any cell is baked.
  runtime::PvsFile file;
  ASSERT_EQ(
      runtime::PvsFile::open_owned(runtime::encode(preprocess::bake_city(city(), options)), file),
      runtime::Status::kOk);
  try {
    explain::explain_excess(city(), file, bake_options(1, 30), explain_options(10));
    ADD_FAILURE() << "cells of other settings were accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cells, its settings give"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace urbanpvs
