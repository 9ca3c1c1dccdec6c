// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-preprocess's options: CLI11 for the command line, nlohmann::json for --config, one
// validation after both are merged so a bad value is reported the same way wherever it came from.
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

#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"

namespace urbanpvs::preprocess {
namespace {

namespace fs = std::filesystem;

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Settings that are text until both sources are merged.
struct TextSettings {
  std::string eye_band;
  std::string coordinates = "auto";
  std::string backend = "cpu";
  std::string method = "hierarchical";
  double default_height = 0;
  bool default_height_given = false;
  bool pixel_given = false;
  std::string config;
};

std::string format_metres(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// "MIN:MAX" in metres.
void parse_band(const std::string& text, double& lo, double& hi) {
  const auto colon = text.find(':');
  try {
    if (colon != std::string::npos) {
      std::size_t n1 = 0, n2 = 0;
      lo = std::stod(text.substr(0, colon), &n1);
      hi = std::stod(text.substr(colon + 1), &n2);
      if (n1 == colon && n2 == text.size() - colon - 1) return;
    }
  } catch (const std::exception&) {
  }
  throw UsageError("--eye-band expects MIN:MAX in metres, got \"" + text + "\"");
}

template <typename Enum>
Enum parse_choice(const std::string& option, const std::string& text,
                  const std::map<std::string, Enum>& choices) {
  const auto it = choices.find(text);
  if (it != choices.end()) return it->second;
  std::string names;
  for (const auto& [name, value] : choices) names += (names.empty() ? "" : ", ") + name;
  throw UsageError(option + " must be one of " + names + ", got \"" + text + "\"");
}

// Applies the --config file's settings to every option the command line did not set.
void apply_config(const std::string& path, CLI::App& app, PreprocessRequest& r, TextSettings& t) {
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
  // Paths in a config file are relative to the file, so a config travels with its data.
  const fs::path base = fs::path(path).parent_path();
  auto relative_to_config = [&](const std::string& p) {
    return fs::path(p).is_absolute() ? p : (base / p).lexically_normal().string();
  };

  for (const auto& [raw_key, value] : config.items()) {
    std::string key = raw_key;
    std::replace(key.begin(), key.end(), '_', '-');
    auto wrong = [&](const char* kind) {
      return UsageError(path + ": \"" + raw_key + "\" must be " + kind);
    };
    auto number = [&]() {
      if (!value.is_number()) throw wrong("a number");
      return value.get<double>();
    };
    auto text_value = [&]() {
      if (!value.is_string()) throw wrong("a string");
      return value.get<std::string>();
    };
    auto flag = [&]() {
      if (!value.is_boolean()) throw wrong("true or false");
      return value.get<bool>();
    };
    const std::map<std::string, std::function<void()>> setters = {
        {"epsilon", [&] { r.bake.cells.epsilon = number(); }},
        {"pixel", [&] { r.bake.pixel = number(), t.pixel_given = true; }},
        {"max-cell-edge", [&] { r.bake.cells.max_cell_edge = number(); }},
        {"eye-band", [&] { t.eye_band = text_value(); }},
        {"region", [&] { r.region_file = relative_to_config(text_value()); }},
        {"default-height", [&] { t.default_height = number(), t.default_height_given = true; }},
        {"level-height", [&] { r.read.level_height = number(); }},
        {"coordinates", [&] { t.coordinates = text_value(); }},
        {"strict", [&] { r.read.strict = flag(); }},
        {"skip-invalid", [&] { (void)flag(); }},
        {"max-height", [&] { r.read.max_height = number(); }},
        {"gap", [&] { r.bake.blocks.gap_tolerance = number(); }},
        {"threads",
         [&] {
           if (!value.is_number_unsigned()) throw wrong("a positive integer");
           r.threads =
               static_cast<unsigned>(std::min<std::uint64_t>(value.get<std::uint64_t>(), 1u << 20));
         }},
        {"backend", [&] { t.backend = text_value(); }},
        {"method", [&] { t.method = text_value(); }},
        {"initial-map",
         [&] {
           if (!value.is_number_integer()) throw wrong("an integer");
           r.bake.initial_map =
               static_cast<int>(std::clamp<std::int64_t>(value.get<std::int64_t>(), -1, 1 << 30));
         }},
        {"max-map",
         [&] {
           if (!value.is_number_integer()) throw wrong("an integer");
           r.bake.max_map =
               static_cast<int>(std::clamp<std::int64_t>(value.get<std::int64_t>(), -1, 1 << 30));
         }},
        {"report", [&] { r.report_file = relative_to_config(text_value()); }},
        {"quiet", [&] { r.quiet = flag(); }},
    };
    const auto setter = setters.find(key);
    if (setter == setters.end())
      throw UsageError(path + ": unknown setting \"" + raw_key +
                       "\" (settings are the long option names, e.g. \"max-cell-edge\")");
    if (app.get_option("--" + key)->count() > 0) continue;  // the command line wins
    setter->second();
  }
}

void finish_and_validate(PreprocessRequest& r, const TextSettings& t) {
  if (!t.eye_band.empty()) parse_band(t.eye_band, r.bake.cells.eye_min, r.bake.cells.eye_max);
  using Coordinates = geometry::ReadOptions::Coordinates;
  r.read.coordinates = parse_choice<Coordinates>("--coordinates", t.coordinates,
                                                 {{"auto", Coordinates::Auto},
                                                  {"geographic", Coordinates::Geographic},
                                                  {"projected", Coordinates::Projected}});
  r.bake.backend = parse_choice<Backend>("--backend", t.backend,
                                         {{"cpu", Backend::Cpu}, {"osmesa", Backend::OsMesa}});
  r.bake.method = parse_choice<Method>(
      "--method", t.method,
      {{"hierarchical", Method::Hierarchical}, {"brute-force", Method::BruteForce}});
  if (t.default_height_given) {
    if (!(t.default_height > 0)) throw UsageError("--default-height must be > 0 m");
    r.read.default_height = t.default_height;
  }
  if (!(r.read.level_height > 0)) throw UsageError("--level-height must be > 0 m");
  if (r.threads < 1 || r.threads > 1024) throw UsageError("--threads must be 1 .. 1024");
  // The pixel size defaults to the largest one that keeps rasterization conservative for ε
  // (thesis 7.2); a larger one is refused with CullMapSettings' own explanation.
  if (!t.pixel_given) r.bake.pixel = CullMapSettings::max_pixel(r.bake.cells.epsilon);
  try {
    if (!(r.bake.cells.epsilon > 0))
      throw std::invalid_argument("--epsilon must be > 0 m, got " +
                                  format_metres(r.bake.cells.epsilon));
    CullMapSettings{r.bake.cells.epsilon, r.bake.pixel}.validate();
    geometry::validate(r.bake.cells);
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
      "file. Long bakes can be killed and continued with --resume."};
  app.name("urbanpvs-preprocess");
  r = PreprocessRequest{};
  r.threads = std::max(1u, std::thread::hardware_concurrency());
  TextSettings t;
  t.eye_band = format_metres(r.bake.cells.eye_min) + ":" + format_metres(r.bake.cells.eye_max);
  const std::string default_band = t.eye_band;

  app.add_option("CITY", r.inputs,
                 "City files: CityJSON 1.0-2.0 or GeoJSON, all in one coordinate system")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", r.output, "PVS file to write; the journal is OUT.journal")
      ->type_name("OUT.pvs")
      ->required();
  app.add_option("--epsilon", r.bake.cells.epsilon,
                 "Occluder shrinking and sample spacing epsilon, in m (thesis 7.2)")
      ->type_name("M")
      ->capture_default_str();
  app.add_option("--pixel", r.bake.pixel,
                 "Cull-map pixel size in m, at most epsilon/(sqrt(2)/2 + 1/128) [default: that "
                 "limit, 1.399 m for epsilon 1 m]")
      ->type_name("M");
  app.add_option("--max-cell-edge", r.bake.cells.max_cell_edge, "Longest view-cell edge in m")
      ->type_name("M")
      ->capture_default_str();
  app.add_option("--eye-band", t.eye_band, "Eye heights above the ground in m, MIN:MAX")
      ->type_name("MIN:MAX")
      ->default_str(default_band);
  app.add_option("--region", r.region_file,
                 "GeoJSON (Multi)Polygons in the city's CRS: where view cells go [default: the "
                 "buildings' bounding rectangle grown by 50 m]")
      ->check(CLI::ExistingFile);
  app.add_option("--default-height", t.default_height,
                 "Height in m of GeoJSON buildings without height attributes [default: none; "
                 "such buildings are objects that occlude nothing, tested up to --max-height]")
      ->type_name("M");
  app.add_option("--level-height", r.read.level_height,
                 "Height in m of one storey, for building:levels")
      ->type_name("M")
      ->capture_default_str();
  app.add_option("--coordinates", t.coordinates,
                 "GeoJSON coordinates: auto, geographic or projected")
      ->type_name("auto|geographic|projected")
      ->capture_default_str();
  app.add_flag("--strict", r.read.strict,
               "Refuse geometry that needs repair (exit 14) instead of repairing it or keeping "
               "the building as an object that occludes nothing");
  app.add_flag("--skip-invalid")
      ->description(
          "Accepted for old scripts; the default now keeps every building (repaired, or "
          "as an object that occludes nothing)");
  app.add_option("--max-height", r.read.max_height,
                 "Tallest plausible building in m: taller input is refused; buildings of "
                 "unknown height are tested up to it")
      ->type_name("M")
      ->check(CLI::Range(1.0, 100000.0))
      ->capture_default_str();
  app.add_option("--gap", r.bake.blocks.gap_tolerance,
                 "Footprints closer than this many m fuse into one block")
      ->type_name("M")
      ->capture_default_str();
  app.add_option("--threads", r.threads,
                 "Worker threads [default: all cores, " + std::to_string(r.threads) + " here]")
      ->type_name("N");
  app.add_option("--backend", t.backend, "Cull-map renderer: cpu or osmesa")
      ->type_name("cpu|osmesa")
      ->capture_default_str();
  app.add_option("--method", t.method,
                 "Visibility test: hierarchical (thesis 5.6) or brute-force (reference)")
      ->type_name("hierarchical|brute-force")
      ->capture_default_str();
  app.add_option("--initial-map", r.bake.initial_map,
                 "Side of the hierarchical test's first cull map, in pixels (8 .. 65536)")
      ->type_name("PIXELS")
      ->capture_default_str();
  app.add_option("--max-map", r.bake.max_map,
                 "Largest cull map, in pixels (initial-map .. 65536); beyond it the samples' "
                 "horizons decide (65536: cull maps alone, grown to cover the city)")
      ->type_name("PIXELS")
      ->capture_default_str();
  app.add_option("--report", r.report_file,
                 "Write a JSON report: settings, input hash, counts, stage times, counters, peak "
                 "memory")
      ->type_name("FILE.json");
  app.add_flag("--resume", r.resume,
               "Continue from OUT.journal when it exists; it must come from the same inputs "
               "and settings");
  app.add_flag("-q,--quiet", r.quiet, "No progress and no summary; errors are still printed");
  app.add_option("--config", t.config,
                 "JSON object of settings keyed by long option name, e.g. {\"epsilon\": 0.5, "
                 "\"eye-band\": \"0:2\"}; paths in it are relative to it; the command line wins")
      ->check(CLI::ExistingFile);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  }
  t.pixel_given = app.get_option("--pixel")->count() > 0;
  t.default_height_given = app.get_option("--default-height")->count() > 0;
  try {
    if (!t.config.empty()) apply_config(t.config, app, r, t);
    finish_and_validate(r, t);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "urbanpvs-preprocess: %s\nRun with --help for more information.\n",
                 e.what());
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace urbanpvs::preprocess
