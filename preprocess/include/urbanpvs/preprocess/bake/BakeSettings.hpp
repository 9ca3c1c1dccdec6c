// SPDX-License-Identifier: GPL-3.0-or-later
// The one table of urbanpvs-preprocess's settings. Each setting is written once (Setting.hpp):
// its key (the long option, the --config key, and with its unit the property stored in the
// file), unit, limits, help text and enum names; its default is the member initializer of the
// struct that holds it (BakeOptions, ReadOptions, PreprocessRequest). The reading, block and
// view-cell settings are the geometry stages' own tables (read_settings, block_settings,
// view_cell_settings), taken over with lift(); the cull-map and run settings are written here.
// From this table come the command-line options, the --config file, the range checks
// (BakeOptions::validate), the properties stored in the file and hashed into the journal's
// fingerprint, and the README's option table (settings_markdown, checked by
// tests/preprocess/BakeSettingsTest.cpp). Adding a bake option means one entry plus its use.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/settings/Setting.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::preprocess {

/// Everything one run of urbanpvs-preprocess needs.
struct PreprocessRequest {
  std::vector<std::string>
      inputs;          ///< city files (CityJSON, CityGML, GeoJSON, OSM), one coordinate system
  std::string output;  ///< the .pvs file; the journal is output + ".journal"
  geometry::ReadOptions read;
  BakeOptions bake;         ///< bake.cells.region is filled from region_file by the run
  std::string region_file;  ///< GeoJSON polygons in the city's CRS; empty: the default region
  unsigned threads = 1;     ///< worker threads (the command line defaults to all cores)
  std::string report_file;  ///< JSON report; empty: none
  bool resume = false;      ///< continue from the journal when there is one
  bool quiet = false;       ///< no progress and no summary (errors are still printed)
  /// How the file codes the PVS: exp-Golomb (format 2.2) or varint (2.0/2.1 readers).
  runtime::PvsCoding pvs_coding = runtime::PvsCoding::kExpGolomb;
};

using geometry::exact;
using geometry::SettingKind;
using geometry::SettingStage;
using Setting = geometry::Setting<PreprocessRequest>;

/// The pixel size used when none is given: the largest that keeps rasterization conservative for
/// ε (thesis 7.2: ε >= k·(√2/2 + 1/128)), within the pixel setting's own limit (a finer pixel
/// is conservative too).
double default_pixel(double epsilon);

/// Every setting, in the order of the pipeline's stages.
const std::vector<Setting>& bake_settings();
/// The setting with this key (underscores read as dashes); nullptr when there is none.
const Setting* find_setting(std::string key);

/// The result's settings of the table's Occluders, Cells and Visibility stages as (property,
/// value) in table order. Stored in every output file (BakeScene::pvs_file) and part of
/// urbanpvs-preprocess's journal fingerprint; bake_city stores exactly these.
std::vector<std::pair<std::string, std::string>> bake_properties(const BakeOptions& options);
/// The inverse of bake_properties: the options a file's properties record (urbanpvs-explain
/// re-bakes cells with them). Settings that bake_properties does not store (the region, the
/// gap of the cells, which the scene takes from the blocks) keep their defaults. Throws
/// std::invalid_argument naming a property that is missing or does not read back.
BakeOptions bake_options_from_properties(
    const std::vector<std::pair<std::string, std::string>>& properties);
/// All result settings of a request (Read stage included), in table order.
std::vector<std::pair<std::string, std::string>> request_properties(const PreprocessRequest& r);

/// The README's option table (Markdown), generated from the table.
std::string settings_markdown();

}  // namespace urbanpvs::preprocess
