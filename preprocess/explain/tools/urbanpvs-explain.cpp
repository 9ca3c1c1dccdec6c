// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-explain CITY... PVS: where a PVS's excess comes from (ExcessBreakdown.hpp). For each
// object in a cell's PVS that the validator did not see from a viewpoint of the cell, the first
// mechanism that accounts for it: a sliver the targets missed, visibility from elsewhere in the
// cell, ε-shrinking, the pixel size, the far field, or the occluder model. Prints a table of
// the causes; --objects-csv and --cells-csv write the same per object and per cell as CSV.
// The bake settings are read from the file; the city must be read as for the bake.
// Exit 0: explained; 1: the validator found misses (the table is still printed); 2: usage; 4:
// the file's PVS is not what its settings bake; 5: a CSV file cannot be written; 10 and above:
// input errors (geometry::exit_code); 20-23: the PVS file cannot be loaded.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "urbanpvs/explain/ExcessBreakdown.hpp"
#include "urbanpvs/explain/ExcessReport.hpp"
#include "urbanpvs/geometry/cells/ViewCellRegion.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/geometry/settings/SettingOptions.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/FileIo.hpp"
#include "urbanpvs/validate/ValidationCommand.hpp"

int main(int argc, char** argv) {
  using namespace urbanpvs;
  CLI::App app{
      "Puts down each object of a PVS that no viewpoint saw to the mechanism that let it in: "
      "seen-finer, elsewhere-in-cell, epsilon, pixel, far-field or occluder-model."};
  std::vector<std::string> inputs;
  explain::ExplainOptions options;
  options.validation.viewpoints = options.validation.tightness_viewpoints = 200;
  options.threads = std::max(1u, std::thread::hardware_concurrency());
  std::string objects_file, cells_file, region_file;
  app.add_option("inputs", inputs, "City files, then the PVS file")->required()->expected(2, -1);
  geometry::ReadOptions read;
  const geometry::SettingOptions<geometry::ReadOptions> read_options(app,
                                                                     geometry::read_settings());
  app.add_option("--viewpoints", options.validation.viewpoints,
                 "Random viewpoints whose excess is explained (those of urbanpvs-validate "
                 "--tightness-viewpoints with the same seed)")
      ->capture_default_str();
  validate::add_target_options(app, options.validation);
  app.add_option("--finer-spacing", options.finer_spacing,
                 "Target spacing of the seen-finer test, as a fraction of --point-spacing "
                 "(0.01 .. 1)")
      ->capture_default_str();
  app.add_option("--cell-viewpoints", options.cell_viewpoints,
                 "Random points of the cell tried by the elsewhere-in-cell test, besides its "
                 "top corners and top-edge middles (0 .. 4096)")
      ->capture_default_str();
  app.add_option("--pixel-divisor", options.pixel_divisor,
                 "The pixel test bakes with pixels this many times smaller (1 .. 16)")
      ->capture_default_str();
  app.add_option("--threads", options.threads,
                 "Threads casting rays and baking cells again [default: all cores]");
  app.add_option("--region", region_file, "The bake's --region file, when it had one");
  app.add_option("--objects-csv", objects_file, "Write the excess per object to this CSV file");
  app.add_option("--cells-csv", cells_file, "Write the excess per cell to this CSV file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : exit_code::kUsage;
  }
  options.validation.tightness_viewpoints = options.validation.viewpoints;
  try {
    options.validate();
    read_options.apply(read);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "urbanpvs-explain: %s\n", e.what());
    return exit_code::kUsage;
  }
  const std::string pvs_path = inputs.back();
  return validate::run_on_city_and_pvs(
      "urbanpvs-explain", inputs, read, [&](const auto& city, const auto& file) {
        preprocess::BakeOptions bake;
        try {
          bake = explain::bake_options_of(file);
        } catch (const std::invalid_argument& e) {
          std::fprintf(stderr, "urbanpvs-explain: %s: %s\n", pvs_path.c_str(), e.what());
          return exit_code::kUsage;
        }
        if (!region_file.empty()) {
          bake.cells.region = geometry::read_region_file(region_file, city.frame);
        }
        const explain::ExcessBreakdown b = explain::explain_excess(city, file, bake, options);
        std::fputs(explain::breakdown_table(b).c_str(), stdout);
        try {
          if (!objects_file.empty())
            runtime::write_file_atomic(objects_file, explain::objects_csv(b, city));
          if (!cells_file.empty()) runtime::write_file_atomic(cells_file, explain::cells_csv(b));
        } catch (const runtime::FileWriteError& e) {
          std::fprintf(stderr, "urbanpvs-explain: %s\n", e.what());
          return exit_code::kOutput;
        }
        return b.validation.misses.empty() ? exit_code::kOk : exit_code::kMisses;
      });
}
