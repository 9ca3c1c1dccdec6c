// SPDX-License-Identifier: GPL-3.0-or-later
// What urbanpvs-validate and urbanpvs-explain share on the command line (header only, for the
// two tools): the target options, and the run on CITY... PVS with the tools' exit codes (input
// errors 10-19, a .pvs that does not load 20-23, anything else 4).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/validate/Validator.hpp"

namespace urbanpvs::validate {

/// --point-spacing, --crack and --seed, bound to `options`.
inline void add_target_options(CLI::App& app, ValidationOptions& options) {
  app.add_option("--point-spacing", options.point_spacing,
                 "Largest distance in m between target points on a surface (0.1 .. 1000)")
      ->type_name("M")
      ->capture_default_str();
  app.add_option("--crack", options.crack,
                 "Openings between buildings narrower than this many m are closed (0 .. 1; "
                 "keep it at most the bake's --gap: wider hides real misses)")
      ->type_name("M")
      ->capture_default_str();
  app.add_option("--seed", options.seed, "Random seed")->capture_default_str();
}

/// The reading settings of this run that differ from those the bake stored in `file` (its
/// properties, e.g. default_height_m = 10), as "key = file's value (this run: value)". Files are
/// not compared: a path may name the same file in other words. A property the file lacks (an
/// older file) is not compared either.
inline std::vector<std::string> reading_differences(const geometry::ReadOptions& read,
                                                    const runtime::PvsFile& file) {
  std::vector<std::string> out;
  for (const auto& s : geometry::read_settings()) {
    if (s.kind == geometry::SettingKind::Path) continue;
    const std::string key = s.property_key(), mine = s.get(read);
    for (std::size_t i = 0; i < file.property_count(); ++i) {
      std::string_view k, v;
      file.property(i, k, v);
      if (k == key && v != mine)
        out.push_back(key + " = " + std::string(v) + " (this run: " + mine + ")");
    }
  }
  return out;
}

/// Reads the city files (all of `inputs` but the last), loads the last as a .pvs file and
/// returns work(city, file), or the exit code of what failed, with the message on stderr
/// prefixed by `tool`.
template <typename Work>
int run_on_city_and_pvs(const char* tool, std::vector<std::string> inputs,
                        const geometry::ReadOptions& read, Work&& work) {
  const std::string pvs_path = inputs.back();
  inputs.pop_back();
  try {
    const geometry::City city = geometry::read_city(inputs, read);
    runtime::PvsFile file;
    runtime::LoadError error;
    if (runtime::PvsFile::open_file(pvs_path.c_str(), file, {}, &error) != runtime::Status::kOk) {
      std::fprintf(stderr, "%s: %s: cannot load: %s\n", tool, pvs_path.c_str(), error.detail);
      return exit_code::for_load(error.status);
    }
    // The ground truth is of the city as read now. Read otherwise than for the bake it may be
    // another city (a default height the bake had and this run lacks makes buildings
    // transparent, and what the bake hid behind them shows up as misses); settings that shape
    // only the occluders (--sloped-roofs, --roof-step) change nothing here, but are named too.
    for (const std::string& d : reading_differences(read, file))
      std::fprintf(stderr,
                   "%s: warning: %s was baked with %s; read the city with the bake's reading "
                   "options, or the ground truth may be of another city\n",
                   tool, pvs_path.c_str(), d.c_str());
    return work(city, file);
  } catch (const geometry::InputError& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return geometry::exit_code(e.problem());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s: %s\n", tool, pvs_path.c_str(), e.what());
    return exit_code::kProcessing;
  }
}

}  // namespace urbanpvs::validate
