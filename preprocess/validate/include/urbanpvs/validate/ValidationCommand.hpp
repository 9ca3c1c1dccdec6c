// SPDX-License-Identifier: GPL-3.0-or-later
// What urbanpvs-validate and urbanpvs-explain share on the command line (header only, for the
// two tools): the target options, and the run on CITY... PVS with the tools' exit codes (input
// errors 10-19, a .pvs that does not load 20-23, anything else 4).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
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
