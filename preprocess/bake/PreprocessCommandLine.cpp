// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-preprocess's options, all from the one settings table (BakeSettings.hpp): CLI11 for the
// command line, nlohmann::json for --config, one validation after both are merged so a bad value
// is reported the same way wherever it came from.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "urbanpvs/geometry/settings/SettingOptions.hpp"
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"

namespace urbanpvs::preprocess {
namespace {

namespace fs = std::filesystem;

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every setting of the table as text, from the command line or the config, until one pass sets
// and checks them all (so a bad value reads the same wherever it came from).
using SettingTexts = std::map<std::string, std::string>;

// A JSON value of the config as the text the setting parses.
std::string config_text(const Setting& s, const nlohmann::json& value, const std::string& path,
                        const std::string& raw_key, const fs::path& base) {
  auto wrong = [&](const char* kind) {
    return UsageError(path + ": \"" + raw_key + "\" must be " + kind);
  };
  switch (s.kind) {
    case SettingKind::Number:
    case SettingKind::Integer: {
      if (!value.is_number()) throw wrong("a number");
      if (value.is_number_integer()) return std::to_string(value.get<std::int64_t>());
      return exact(value.get<double>());
    }
    case SettingKind::Flag:
      if (!value.is_boolean()) throw wrong("true or false");
      return value.get<bool>() ? "true" : "false";
    case SettingKind::Path: {
      if (!value.is_string()) throw wrong("a string");
      // Paths in a config file are relative to the file, so a config travels with its data.
      const fs::path p = value.get<std::string>();
      return p.is_absolute() ? p.string() : (base / p).lexically_normal().string();
    }
    case SettingKind::Choice:
    case SettingKind::Band:
    case SettingKind::Text:
      break;
  }
  if (!value.is_string()) throw wrong("a string");
  return value.get<std::string>();
}

// Adds the --config file's settings that the command line did not give.
void apply_config(const std::string& path, SettingTexts& texts) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw UsageError(path + ": cannot read the config file");
  nlohmann::json config;
  try {
    config = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw UsageError(path + ": invalid JSON: " + e.what());
  }
  if (!config.is_object()) throw UsageError(path + ": the config must be a JSON object");
  const fs::path base = fs::path(path).parent_path();
  for (const auto& [raw_key, value] : config.items()) {
    if (raw_key == "skip-invalid" || raw_key == "skip_invalid") continue;  // old scripts
    const Setting* s = find_setting(raw_key);
    if (!s)
      throw UsageError(path + ": unknown setting \"" + raw_key +
                       "\" (settings are the long option names, e.g. \"max-cell-edge\")");
    if (texts.count(s->key)) continue;  // the command line wins
    texts[s->key] = config_text(*s, value, path, raw_key, base);
  }
}

// Sets every given setting (range checks: the table's), then the cross-setting rules of the
// bake (BakeOptions::validate: the coupling of epsilon and the pixel, thesis 7.2), once.
void finish_and_validate(PreprocessRequest& r, const SettingTexts& texts) {
  try {
    for (const Setting& s : bake_settings())
      if (const auto it = texts.find(s.key); it != texts.end()) s.set(r, it->second);
    // The pixel size defaults to the largest one that keeps rasterization conservative for ε
    // (thesis 7.2); a larger one is refused with CullMapSettings' own explanation.
    if (!texts.count("pixel")) r.bake.pixel = default_pixel(r.bake.cells.epsilon);
    // --cells FILE is --region FILE by another name.
    if (r.bake.cells.placement == geometry::ViewCellOptions::Placement::File) {
      if (!r.region_file.empty())
        throw UsageError("--cells " + r.bake.cells.region_file + " and --region " + r.region_file +
                         " both name a region: give one");
      r.region_file = r.bake.cells.region_file;
    }
    r.bake.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

std::optional<int> parse_preprocess_command_line(int argc, const char* const* argv,
                                                 PreprocessRequest& r) {
  CLI::App app{
      "Precomputes the potentially visible set (PVS) of every view cell of a city (Wonka's "
      "from-region visibility: shrunk occluders, cull maps, hierarchical test) and writes a .pvs "
      "file. Long bakes can be killed and continued with --resume. Every setting can also be "
      "given in a --config file; README.md has the table of them."};
  app.name("urbanpvs-preprocess");
  r = PreprocessRequest{};
  r.threads = std::max(1u, std::min(1024u, std::thread::hardware_concurrency()));
  const PreprocessRequest defaults = r;

  app.add_option("CITY", r.inputs,
                 "City files: CityJSON 1.0-2.0 (or .city.jsonl), CityGML 1.0-3.0, GeoJSON, "
                 "OpenStreetMap, Shapefile, GeoPackage or FlatGeobuf, all in one coordinate "
                 "system")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", r.output, "PVS file to write; the journal is OUT.journal")
      ->type_name("OUT.pvs")
      ->required();
  // The settings, from the one table (BakeSettings.hpp).
  const geometry::SettingOptions<PreprocessRequest> settings(app, bake_settings(), defaults);
  app.add_flag("--skip-invalid")
      ->description(
          "Accepted for old scripts; the default now keeps every building (repaired, or "
          "as an object that occludes nothing)");
  app.add_flag("--resume", r.resume,
               "Continue from OUT.journal when it exists; it must come from the same inputs "
               "and settings");
  std::string config;
  app.add_option("--config", config,
                 "JSON object of settings keyed by long option name, e.g. {\"epsilon\": 0.5, "
                 "\"eye-band\": \"0:2\"}; paths in it are relative to it; the command line wins")
      ->check(CLI::ExistingFile);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  }
  SettingTexts texts = settings.given();
  try {
    if (!config.empty()) apply_config(config, texts);
    finish_and_validate(r, texts);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "urbanpvs-preprocess: %s\nRun with --help for more information.\n",
                 e.what());
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace urbanpvs::preprocess
