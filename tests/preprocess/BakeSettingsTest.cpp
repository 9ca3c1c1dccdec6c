// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table (BakeSettings.hpp) is the only place a setting is written: every entry is
// an option of --help, a key of --config, a property of the file (when it changes the result)
// and a row of the README's option table; and a value set through any of them reads back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/geometry/occluders/BlockSettings.hpp"
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"

namespace fs = std::filesystem;
using namespace urbanpvs::preprocess;
namespace geometry = urbanpvs::geometry;

namespace {

const std::string kCity = std::string(URBANPVS_SOURCE_DIR) + "/cities/sample/district.city.json";

std::optional<int> parse(std::vector<std::string> args, PreprocessRequest& r) {
  args.insert(args.begin(), "urbanpvs-preprocess");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  return parse_preprocess_command_line(int(argv.size()), argv.data(), r);
}

// The standard output of a command.
std::string output_of(const std::string& command) {
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
      out.append(buffer, n);
    ::pclose(pipe);
  }
  return out;
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The setting's default as a value of a --config file.
nlohmann::json json_value(const Setting& s, const std::string& text) {
  switch (s.kind) {
    case SettingKind::Number:
    case SettingKind::Integer:
      return std::stod(text);
    case SettingKind::Flag:
      return text == "true";
    default:
      return text;
  }
}

bool has_file_default(const Setting& s) {
  return s.kind == SettingKind::Path || s.kind == SettingKind::Text || s.key == "default-height" ||
         s.key == "roof-step";  // "none", "off" are no values
}

}  // namespace

TEST(BakeSettings, EverySettingIsAnOptionOfHelp) {
  PreprocessRequest r;
  testing::internal::CaptureStdout();
  EXPECT_EQ(parse({"--help"}, r), 0);
  std::cout.flush();
  const std::string help = testing::internal::GetCapturedStdout();
  for (const Setting& s : bake_settings()) {
    EXPECT_NE(help.find("--" + s.key + " "), std::string::npos) << s.key << " is not in --help";
    EXPECT_NE(help.find(s.help.substr(0, 30)), std::string::npos) << s.key << ": help text";
  }
}

TEST(BakeSettings, EverySettingIsAConfigKeyAndTheCommandLineWins) {
  PreprocessRequest defaults;
  ASSERT_EQ(parse({kCity, "-o", "x.pvs"}, defaults), std::nullopt);
  const fs::path config =
      fs::temp_directory_path() / ("urbanpvs_settings_" + std::to_string(::getpid()) + ".json");
  for (const Setting& s : bake_settings()) {
    if (has_file_default(s)) continue;
    SCOPED_TRACE(s.key);
    // The value each setting has by default, given in a config alone: accepted, same request.
    std::ofstream(config) << nlohmann::json{{s.key, json_value(s, s.get(defaults))}}.dump();
    PreprocessRequest r;
    ASSERT_EQ(parse({kCity, "-o", "x.pvs", "--config", config.string()}, r), std::nullopt);
    for (const Setting& t : bake_settings()) EXPECT_EQ(t.get(r), t.get(defaults)) << t.key;
  }
  // A config value is used unless the command line gives one.
  std::ofstream(config) << R"({"max_cell_edge": 25, "eye-band": "0.5:1.5", "method": "brute-force",
                              "strict": true, "initial-map": 64})";
  PreprocessRequest r;
  ASSERT_EQ(parse({kCity, "-o", "x.pvs", "--config", config.string(), "--initial-map", "32"}, r),
            std::nullopt);
  EXPECT_EQ(r.bake.cells.max_cell_edge, 25);
  EXPECT_EQ(r.bake.cells.eye_min, 0.5);
  EXPECT_EQ(r.bake.cells.eye_max, 1.5);
  EXPECT_EQ(r.bake.method, Method::BruteForce);
  EXPECT_TRUE(r.read.strict);
  EXPECT_EQ(r.bake.initial_map, 32);
  fs::remove(config);
}

TEST(BakeSettings, OutOfLimitsIsRefusedWithTheOptionsName) {
  for (const Setting& s : bake_settings()) {
    if (s.kind != SettingKind::Number && s.kind != SettingKind::Integer) continue;
    SCOPED_TRACE(s.key);
    PreprocessRequest r;
    for (double bad : {s.min - 1, s.max * 2 + 1}) {
      try {
        s.set(r, std::to_string(bad));
        ADD_FAILURE() << bad << " was accepted";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("--" + s.key + " must be " + s.limits_text()),
                  std::string::npos)
            << e.what();
      }
    }
  }
}

TEST(BakeSettings, EveryResultSettingIsAPropertyOfTheFile) {
  PreprocessRequest r;
  ASSERT_EQ(parse({kCity, "-o", "x.pvs"}, r), std::nullopt);
  const auto stored = result_settings(r, 0);
  auto has = [&](const std::string& key) {
    for (const auto& [k, v] : stored)
      if (k == key) return true;
    return false;
  };
  for (const Setting& s : bake_settings()) {
    SCOPED_TRACE(s.key);
    EXPECT_EQ(has(s.property_key()), s.changes_result());
  }
}

TEST(BakeSettings, TheReadmeHasTheGeneratedTable) {
  const std::string readme = text_of(fs::path(URBANPVS_SOURCE_DIR) / "README.md");
  const std::string table = settings_markdown();
  EXPECT_NE(readme.find(table), std::string::npos)
      << "README.md's option table is out of date; the table is now:\n"
      << table;
  for (const Setting& s : bake_settings())
    EXPECT_NE(readme.find("| `--" + s.key + "` |"), std::string::npos) << s.key;
}

// The table's limits of the occluder and cell settings are checked again by the stages that own
// them (geometry::validate, BakeOptions::validate, for library callers): the owners accept the
// table's whole range, so the table never promises a value that a stage then refuses.
TEST(BakeSettings, TheStagesAcceptTheTablesWholeRange) {
  for (const Setting& s : bake_settings()) {
    if (s.kind != SettingKind::Number && s.kind != SettingKind::Integer) continue;
    if (s.stage != SettingStage::Occluders && s.stage != SettingStage::Cells &&
        s.stage != SettingStage::Visibility)
      continue;
    for (double v : {s.min, s.max}) {
      SCOPED_TRACE(s.key + " = " + std::to_string(v));
      PreprocessRequest r;
      if (s.key == "max-map") r.bake.initial_map = 8;      // max-map >= initial-map
      if (s.key == "initial-map") r.bake.max_map = 65536;  // initial-map <= max-map
      ASSERT_NO_THROW(s.set(r, std::to_string(v)));
      r.bake.cells.gap = r.bake.blocks.gap_tolerance;  // as BakeScene hands it on
      if (s.key != "pixel") r.bake.pixel = default_pixel(r.bake.cells.epsilon);
      if (s.key == "pixel") r.bake.cells.epsilon = 1000;  // the largest pixel needs a large ε
      EXPECT_NO_THROW(r.bake.validate());
    }
  }
}

// The other direction: a stage refuses exactly what the table refuses, with the table's words,
// because it checks its options against the table (geometry::check_limits).
TEST(BakeSettings, TheStagesRefuseWhatTheTableRefuses) {
  geometry::ViewCellOptions cells;
  cells.max_cell_edge = 0.25;
  try {
    geometry::validate(cells);
    ADD_FAILURE() << "max_cell_edge 0.25 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--max-cell-edge must be 0.5 .. 10000 m, got \"0.25\"");
  }
  BakeOptions bake;
  bake.max_map = 1 << 20;
  try {
    bake.validate();
    ADD_FAILURE() << "max_map 2^20 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--max-map must be 8 .. 65536 pixels, got \"1048576\"");
  }
  bake = BakeOptions{};
  bake.blocks.gap_tolerance = -1;
  EXPECT_THROW(bake.validate(), std::invalid_argument);
}

// The bake's table takes the stages' tables over unchanged: one entry per setting, wherever it
// is used.
TEST(BakeSettings, TheStagesTablesAreTakenOverUnchanged) {
  auto same = [](const auto& stage_setting) {
    const Setting* s = find_setting(stage_setting.key);
    ASSERT_NE(s, nullptr) << stage_setting.key;
    EXPECT_EQ(s->help, stage_setting.help);
    EXPECT_EQ(s->limits_text(), stage_setting.limits_text());
    EXPECT_EQ(s->stage, stage_setting.stage);
  };
  for (const auto& s : geometry::read_settings()) same(s);
  for (const auto& s : geometry::block_settings()) same(s);
  for (const auto& s : geometry::view_cell_settings())
    if (s.key != "gap") same(s);  // the bake's gap is the blocks' one
}

// Every tool that reads a city offers the same reading options, with the same help.
TEST(BakeSettings, EveryToolReadsCitiesWithTheSameOptions) {
  std::string tools = URBANPVS_CITY_TOOLS;
  for (std::size_t at = 0; at <= tools.size();) {
    const std::size_t bar = std::min(tools.find('|', at), tools.size());
    const std::string tool = tools.substr(at, bar - at);
    at = bar + 1;
    SCOPED_TRACE(tool);
    const std::string help = output_of("'" + tool + "' --help");
    ASSERT_FALSE(help.empty());
    for (const auto& s : geometry::read_settings()) {
      EXPECT_NE(help.find("--" + s.key + " "), std::string::npos) << s.key;
      EXPECT_NE(help.find(s.help.substr(0, 30)), std::string::npos) << s.key << ": help text";
    }
  }
}

// urbanpvs-explain bakes cells again with the options a file stores: every stored setting, set
// to a value other than its default, reads back from the file's properties.
TEST(BakeSettings, TheFilesPropertiesGiveBackTheBakeOptions) {
  PreprocessRequest r;
  const auto defaults = bake_properties(r.bake);
  for (const auto& property : defaults) {
    const std::string& key = property.first;  // lambdas capture it in clang 14 too
    const auto s = std::find_if(bake_settings().begin(), bake_settings().end(),
                                [&](const Setting& t) { return t.property_key() == key; });
    ASSERT_NE(s, bake_settings().end()) << key;
    const double v = s->min + 0.37 * (s->max - s->min);
    switch (s->kind) {
      case SettingKind::Number:
        s->set(r, geometry::exact(v));
        break;
      case SettingKind::Integer:
        s->set(r, std::to_string(static_cast<long long>(std::floor(v))));
        break;
      case SettingKind::Band:
        s->set(r, geometry::exact(v) + ":" + geometry::exact(s->max));
        break;
      case SettingKind::Flag:
        s->set(r, s->get(r) == "true" ? "false" : "true");
        break;
      case SettingKind::Choice: {  // another choice that stands for itself (not "FILE")
        const std::string current = s->get(r);
        for (const std::string& c : s->choices) {
          if (c == current) continue;
          try {
            s->set(r, c);
            break;
          } catch (const std::invalid_argument&) {
          }
        }
        break;
      }
      default:
        s->set(r, "x");
    }
  }
  const auto stored = bake_properties(r.bake);
  for (std::size_t i = 0; i < stored.size(); ++i)
    EXPECT_NE(stored[i].second, defaults[i].second) << stored[i].first;
  EXPECT_EQ(bake_properties(bake_options_from_properties(stored)), stored);

  auto missing = stored;
  missing.erase(missing.begin());
  try {
    bake_options_from_properties(missing);
    ADD_FAILURE() << "a missing property was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "the file has no property " + stored.front().first);
  }
  // A file from before --far-outline-tolerance was baked with exact outlines.
  auto older = stored;
  std::erase_if(older, [](const auto& p) { return p.first == "far_outline_tolerance_m"; });
  ASSERT_EQ(older.size() + 1, stored.size());
  EXPECT_EQ(bake_options_from_properties(older).far_outline_tolerance, 0.0);
  auto garbled = stored;
  const auto epsilon = std::find_if(garbled.begin(), garbled.end(),
                                    [](const auto& p) { return p.first == "epsilon_m"; });
  ASSERT_NE(epsilon, garbled.end());
  epsilon->second = "one";
  try {
    bake_options_from_properties(garbled);
    ADD_FAILURE() << "an unreadable property was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--epsilon expects a number, got \"one\"");
  }
}
