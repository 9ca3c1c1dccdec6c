// SPDX-License-Identifier: GPL-3.0-or-later
// The one table of urbanpvs-preprocess's settings. Each setting is written once: its key (the
// long option, the --config key, and with its unit the property stored in the file), unit,
// limits, help text and enum names; its default is the member initializer of the struct that
// holds it (BakeOptions, ReadOptions, PreprocessRequest). From this table come the command-line
// options, the --config file, the range checks, the properties stored in the file and hashed
// into the journal's fingerprint, and the README's option table (settings_markdown, checked by
// tests/preprocess/BakeSettingsTest.cpp). Adding a bake option means one entry here plus its use.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"

namespace urbanpvs::preprocess {

/// Everything one run of urbanpvs-preprocess needs.
struct PreprocessRequest {
  std::vector<std::string> inputs;  ///< city files (CityJSON, GeoJSON), one coordinate system
  std::string output;               ///< the .pvs file; the journal is output + ".journal"
  geometry::ReadOptions read;
  BakeOptions bake;         ///< bake.cells.region is filled from region_file by the run
  std::string region_file;  ///< GeoJSON polygons in the city's CRS; empty: the default region
  unsigned threads = 1;     ///< worker threads (the command line defaults to all cores)
  std::string report_file;  ///< JSON report; empty: none
  bool resume = false;      ///< continue from the journal when there is one
  bool quiet = false;       ///< no progress and no summary (errors are still printed)
};

/// Where a setting acts, in the order of the pipeline. Read, Cells, Occluders and Visibility
/// change the result: they are stored in the file and part of the journal's fingerprint.
enum class SettingStage { Read, Occluders, Cells, Visibility, Run };

enum class SettingKind {
  Number,   ///< a double, checked against [min, max]
  Integer,  ///< an integer, checked against [min, max]
  Flag,     ///< true / false (on the command line: present or not)
  Choice,   ///< one of `choices`
  Band,     ///< "MIN:MAX" in the unit
  Path,     ///< a file name; in a --config file relative to the config
};

struct Setting {
  std::string key;   ///< "max-cell-edge": option --max-cell-edge, config key (or max_cell_edge)
  std::string unit;  ///< "m", "pixels" or "" (none)
  SettingStage stage = SettingStage::Run;
  SettingKind kind = SettingKind::Number;
  std::string help;
  double min = 0, max = 0;           ///< inclusive limits (Number, Integer)
  std::vector<std::string> choices;  ///< Choice: names in the enum's order
  /// Text shown as the default when it is not the member's value ("all cores", "none").
  std::string default_text;
  /// The value as text: exact (the shortest text that reads back to the same double).
  std::function<std::string(const PreprocessRequest&)> get;
  /// Sets the value from text (as given on the command line or converted from JSON). Throws
  /// std::invalid_argument "--key ..." when the text does not parse or is out of the limits.
  std::function<void(PreprocessRequest&, const std::string&)> set;

  bool changes_result() const { return stage != SettingStage::Run; }
  /// The key of the file's property: "max_cell_edge_m".
  std::string property_key() const;
  /// "0.01 .. 1000 m", "cpu | osmesa", "" for flags and paths.
  std::string limits_text() const;
};

/// The shortest text that reads back to the same double: equal settings give equal text (and so
/// equal fingerprints), different ones different text.
std::string exact(double v);

/// Every setting, in the order of the pipeline's stages.
const std::vector<Setting>& bake_settings();
/// The setting with this key (underscores read as dashes); nullptr when there is none.
const Setting* find_setting(std::string key);

/// The result's settings of the table's Occluders, Cells and Visibility stages as (property,
/// value) in table order. Stored in every output file (BakeScene::pvs_file) and part of
/// urbanpvs-preprocess's journal fingerprint; bake_city stores exactly these.
std::vector<std::pair<std::string, std::string>> bake_properties(const BakeOptions& options);
/// All result settings of a request (Read stage included), in table order.
std::vector<std::pair<std::string, std::string>> request_properties(const PreprocessRequest& r);

/// The README's option table (Markdown), generated from the table.
std::string settings_markdown();

}  // namespace urbanpvs::preprocess
