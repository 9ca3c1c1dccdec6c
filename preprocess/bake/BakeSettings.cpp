// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/geometry/occluders/BlockSettings.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"

namespace urbanpvs::preprocess {
namespace {

using R = PreprocessRequest;

template <typename Inner>
void take_over(std::vector<Setting>& t, const geometry::SettingTable<Inner>& stage,
               std::function<Inner&(R&)> part, const std::string& leave_out = "") {
  for (const geometry::Setting<Inner>& s : stage)
    if (s.key != leave_out) t.push_back(geometry::lift<R, Inner>(s, part));
}

std::vector<Setting> make_table() {
  using S = SettingStage;
  std::vector<Setting> t;
  // ---- reading, blocks and occluders: the geometry stages' tables (thesis 7) ----
  take_over<geometry::ReadOptions>(t, geometry::read_settings(),
                                   [](R& r) -> geometry::ReadOptions& { return r.read; });
  take_over<geometry::BlockOptions>(t, geometry::block_settings(),
                                    [](R& r) -> geometry::BlockOptions& { return r.bake.blocks; });
  // ---- view cells (thesis 5.3). Their gap is the blocks' (BakeScene hands it on), so free
  // space and blocks fuse the same footprints; the region comes from a file. ----
  std::vector<Setting> cells;
  take_over<geometry::ViewCellOptions>(
      cells, geometry::view_cell_settings(),
      [](R& r) -> geometry::ViewCellOptions& { return r.bake.cells; }, "gap");
  Setting region = geometry::path_setting<R>(
      "region", S::Cells, "GeoJSON (Multi)Polygons in the city's CRS: where view cells go",
      [](R& r) -> std::string& { return r.region_file; });
  region.default_text = "the buildings' bounding rectangles grown by --margin";
  region.existing_file = true;
  const auto after_band = std::find_if(cells.begin(), cells.end(),
                                       [](const Setting& s) { return s.key == "eye-band"; });
  cells.insert(after_band == cells.end() ? cells.end() : after_band + 1, std::move(region));
  t.insert(t.end(), cells.begin(), cells.end());
  // ---- cull maps and the hierarchical test (thesis 4, 5.6) ----
  Setting pixel = geometry::number_setting<R>(
      "pixel", "m", S::Visibility, 0.001, 1000,
      "Cull-map pixel size, at most epsilon/(sqrt(2)/2 + 1/128) (thesis 7.2)",
      [](R& r) -> double& { return r.bake.pixel; });
  pixel.default_text = "that limit, 1.399 for epsilon 1";
  t.push_back(std::move(pixel));
  t.push_back(geometry::choice_setting<Backend, R>(
      "backend", S::Visibility, {"cpu", "osmesa"},
      "Cull-map renderer: the CPU reference or OSMesa (OpenGL)",
      [](R& r) -> Backend& { return r.bake.backend; }));
  t.push_back(geometry::choice_setting<Method, R>(
      "method", S::Visibility, {"hierarchical", "brute-force"},
      "Visibility test: hierarchical (thesis 5.6) or brute force",
      [](R& r) -> Method& { return r.bake.method; }));
  t.push_back(geometry::integer_setting<int, R>("initial-map", "pixels", S::Visibility, 8, 65536,
                                                "Side of the hierarchical test's first cull map",
                                                [](R& r) -> int& { return r.bake.initial_map; }));
  t.push_back(geometry::integer_setting<int, R>(
      "max-map", "pixels", S::Visibility, 8, 65536,
      "Largest cull map (at least --initial-map); beyond it the samples' horizons decide "
      "(65536: cull maps alone, grown to cover the city)",
      [](R& r) -> int& { return r.bake.max_map; }));
  Setting far_outlines = geometry::number_setting<R>(
      "far-outline-tolerance", "m", S::Visibility, 0, 10,
      "From " + std::to_string(BakeOptions::kFarOutlineRatio) +
          " times this distance on, the samples' horizons take each occluder by its outline "
          "with corners cut inwards by up to this: fewer walls, never a larger occluder (0: "
          "exact outlines)",
      [](R& r) -> double& { return r.bake.far_outline_tolerance; });
  far_outlines.value_before_it = "0";  // files of before 2026-12-04 used exact outlines
  t.push_back(std::move(far_outlines));
  // ---- the run and the file (no effect on the PVS) ----
  t.push_back(geometry::choice_setting<runtime::PvsCoding, R>(
      "pvs-coding", S::Run, {"varint", "exp-golomb"},
      "PVS coding of the file: exp-golomb (format 2.2, the smaller) or varint (format 2.0/2.1, "
      "for engines that ship an older reader)",
      [](R& r) -> runtime::PvsCoding& { return r.pvs_coding; }));
  Setting threads =
      geometry::integer_setting<unsigned, R>("threads", "", S::Run, 1, 1024, "Worker threads",
                                             [](R& r) -> unsigned& { return r.threads; });
  threads.default_text = "all cores";
  t.push_back(std::move(threads));
  t.push_back(geometry::path_setting<R>(
      "report", S::Run,
      "Write a JSON report: settings, input hash, counts, stage times, counters, peak memory",
      [](R& r) -> std::string& { return r.report_file; }));
  Setting quiet = geometry::flag_setting<R>("quiet", S::Run,
                                            "No progress and no summary; errors are still printed",
                                            [](R& r) -> bool& { return r.quiet; });
  quiet.short_name = "q";
  t.push_back(std::move(quiet));
  return t;
}

}  // namespace

const std::vector<Setting>& bake_settings() {
  static const std::vector<Setting> table = make_table();
  return table;
}

double default_pixel(double epsilon) {
  return std::min(CullMapSettings::max_pixel(epsilon), find_setting("pixel")->max);
}

const Setting* find_setting(std::string key) {
  return geometry::find_setting(bake_settings(), std::move(key));
}

std::vector<std::pair<std::string, std::string>> bake_properties(const BakeOptions& options) {
  PreprocessRequest r;
  r.bake = options;
  std::vector<std::pair<std::string, std::string>> out;
  for (const Setting& s : bake_settings())
    if (s.changes_result() && s.stage != SettingStage::Read && s.kind != SettingKind::Path)
      out.emplace_back(s.property_key(), s.get(r));
  return out;
}

BakeOptions bake_options_from_properties(
    const std::vector<std::pair<std::string, std::string>>& properties) {
  PreprocessRequest r;
  for (const auto& property : bake_properties(r.bake)) {
    // A named reference, not a structured binding: lambdas may capture it in every compiler
    // the project builds with (clang 14 cannot capture bindings).
    const std::string& key = property.first;
    const auto stored = std::find_if(properties.begin(), properties.end(),
                                     [&](const auto& p) { return p.first == key; });
    const auto setting = std::find_if(bake_settings().begin(), bake_settings().end(),
                                      [&](const Setting& s) { return s.property_key() == key; });
    // A file older than the setting was made with the value it had before it existed.
    if (stored == properties.end() && setting->value_before_it.empty())
      throw std::invalid_argument("the file has no property " + key);
    setting->set(r, stored != properties.end() ? stored->second : setting->value_before_it);
  }
  return r.bake;
}

std::vector<std::pair<std::string, std::string>> request_properties(const PreprocessRequest& r) {
  std::vector<std::pair<std::string, std::string>> out = bake_properties(r.bake);
  for (const Setting& s : bake_settings())
    if (s.stage == SettingStage::Read) out.emplace_back(s.property_key(), s.get(r));
  return out;
}

std::string settings_markdown() {
  const PreprocessRequest defaults;
  const char* stage_names[] = {"reading", "occluders", "view cells", "visibility", "run"};
  std::string out =
      "| option | stage | default | limits | stored as | what it does |\n"
      "|---|---|---|---|---|---|\n";
  for (const Setting& s : bake_settings()) {
    const std::string value = s.default_shown(defaults);
    std::string limits;  // a choice's "a | b" must not split the table's cells
    for (char c : s.limits_text()) limits += c == '|' ? std::string("\\|") : std::string(1, c);
    out += "| `--" + s.key + "` | " + stage_names[static_cast<int>(s.stage)] + " | " + value +
           " | " + limits + " | " +
           (s.changes_result() ? "`" + s.property_key() + "`" : std::string("-")) + " | " + s.help +
           " |\n";
  }
  return out;
}

}  // namespace urbanpvs::preprocess
