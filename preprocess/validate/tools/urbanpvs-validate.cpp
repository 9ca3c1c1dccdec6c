// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-validate CITY... PVS: an independent ground truth for a PVS file (see Validator.hpp).
// The ground truth is the input's own surfaces as the readers give them (CityObject::surfaces:
// CityJSON's surfaces of the chosen LoD, GeoJSON's extruded footprints), never the occluders
// derived from them: every surface polygon of an occluding object blocks, the ground under a
// building is solid, an object without valid occluder geometry blocks nothing and may be
// anywhere in its box. Targets are points over all surfaces (--point-spacing); cracks narrower
// than --crack are closed. From the PVS file only its object ids, cells and PVSs are read.
// Exit 0: no miss; 1: misses found (listed); 2: usage (an option out of its limits too); 4: the
// file does not belong to the city or cannot be read; 5: the --cells-csv file cannot be written;
// 10 and above: input errors, with urbanpvs-preprocess's codes (geometry::exit_code).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/geometry/settings/SettingOptions.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/FileIo.hpp"
#include "urbanpvs/validate/ValidationCommand.hpp"

int main(int argc, char** argv) {
  using namespace urbanpvs;
  CLI::App app{
      "Checks a PVS file against ray casting in the input's own surfaces: every object seen "
      "from a random viewpoint of a cell but missing from its PVS is a miss."};
  std::vector<std::string> inputs;
  validate::ValidationOptions options;
  app.add_option("inputs", inputs, "City files, then the PVS file")->required()->expected(2, -1);
  // The city must be read as for the bake: the bake's own reading options (one table).
  geometry::ReadOptions read;
  const geometry::SettingOptions<geometry::ReadOptions> read_options(app,
                                                                     geometry::read_settings());
  app.add_option("--viewpoints", options.viewpoints, "Random viewpoints checked")
      ->capture_default_str();
  app.add_option("--tightness-viewpoints", options.tightness_viewpoints,
                 "Viewpoints that also count the objects seen")
      ->capture_default_str();
  app.add_option("--tightness-cells", options.tightness_cells,
                 "Distinct random cells whose tightness is measured over several viewpoints "
                 "each: |PVS| over the objects seen from any of them (0: off)")
      ->capture_default_str();
  app.add_option("--viewpoints-per-cell", options.viewpoints_per_cell,
                 "Viewpoints of each of the --tightness-cells (1 .. 1024)")
      ->capture_default_str();
  std::string cells_file;
  app.add_option("--cells-csv", cells_file,
                 "Write each of the --tightness-cells to this CSV file: cell,pvs,seen,tightness");
  validate::add_target_options(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : exit_code::kUsage;
  }
  try {
    options.validate();
    read_options.apply(read);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "urbanpvs-validate: %s\n", e.what());
    return exit_code::kUsage;
  }
  return validate::run_on_city_and_pvs(
      "urbanpvs-validate", inputs, read, [&](const auto& city, const auto& file) {
        const validate::ValidationReport r = validate::validate(city, file, options);
        std::printf("viewpoints: %zu, rays: %zu, misses: %zu\n", r.viewpoints, r.rays,
                    r.misses.size());
        const std::size_t measured = std::min(options.viewpoints, options.tightness_viewpoints);
        if (measured > 0) {
          std::printf(
              "tightness:  %.3f (mean |PVS| %.1f / mean objects seen %.1f over %zu viewpoints)\n",
              r.tightness(), double(r.pvs_total) / double(measured),
              double(r.seen_total) / double(measured), measured);
        }
        if (!r.cells.empty()) {
          const validate::CellTightnessStats t = validate::cell_tightness_stats(r.cells);
          std::printf(
              "cell tightness: mean %.3f, median %.3f, p90 %.3f over %zu cells x %zu viewpoints "
              "(|PVS| / objects seen from any of them; %zu cells saw nothing)\n",
              t.mean, t.median, t.p90, t.cells, options.viewpoints_per_cell, t.saw_nothing);
        }
        if (!cells_file.empty()) {
          try {
            runtime::write_file_atomic(cells_file, validate::cell_tightness_csv(r.cells));
          } catch (const runtime::FileWriteError& e) {
            std::fprintf(stderr, "urbanpvs-validate: %s\n", e.what());
            return exit_code::kOutput;
          }
        }
        for (std::size_t i = 0; i < r.misses.size() && i < 20; ++i) {
          const validate::Miss& m = r.misses[i];
          std::printf("MISS cell %u viewpoint (%.3f, %.3f, %.3f) sees %s at (%.3f, %.3f, %.3f)\n",
                      m.cell, m.viewpoint.x, m.viewpoint.y, m.viewpoint.z, m.object_id.c_str(),
                      m.target.x, m.target.y, m.target.z);
        }
        return r.misses.empty() ? exit_code::kOk : exit_code::kMisses;
      });
}
