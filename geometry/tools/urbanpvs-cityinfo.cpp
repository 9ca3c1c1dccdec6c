// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-cityinfo: reads city files and prints what urbanpvs makes of them: objects, extent,
// heights, repairs, blocks and shrunk occluders; optionally draws them as an SVG map.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "urbanpvs/geometry/cells/SvgMap.hpp"
#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/geometry/occluders/BlockSettings.hpp"
#include "urbanpvs/geometry/occluders/Blocks.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/geometry/settings/SettingOptions.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/FileIo.hpp"

namespace {

using namespace urbanpvs::geometry;

constexpr int kExitUsage = urbanpvs::exit_code::kUsage;
constexpr int kExitProcessing = urbanpvs::exit_code::kProcessing;
constexpr int kExitOutput = urbanpvs::exit_code::kOutput;

void print_summary(const City& city, const std::vector<Block>& blocks,
                   const std::vector<Occluder>& occluders, double epsilon) {
  std::printf("files:       ");
  for (const std::string& s : city.sources) std::printf("%s ", s.c_str());
  std::printf("\ncoordinates: %s\n", city.report.coordinate_note.c_str());
  if (city.frame.kind == LocalFrame::Kind::Projected)
    std::printf("local frame: %s, origin %.3f %.3f %.3f\n",
                city.frame.crs.empty() ? "(no CRS)" : city.frame.crs.c_str(), city.frame.origin[0],
                city.frame.origin[1], city.frame.origin[2]);
  else
    std::printf("local frame: east-north-up around lon %.7f lat %.7f\n", city.frame.origin_lon,
                city.frame.origin_lat);

  std::size_t prisms = 0, without = 0;
  std::vector<double> heights;
  double footprint_area = 0;
  for (const CityObject& o : city.objects) {
    prisms += o.occluders.size();
    without += o.occluders.empty();
    heights.push_back(o.bbox.zmax - o.ground_z);
    for (const Polygon& p : o.footprint) footprint_area += area(p);
  }
  std::printf("objects:     %zu (%zu occluder prisms; %zu objects without occluder)\n",
              city.objects.size(), prisms, without);
  if (!city.report.ignored_types.empty()) {
    std::printf("ignored:    ");
    for (const auto& [type, n] : city.report.ignored_types) std::printf(" %s %zu", type.c_str(), n);
    std::printf("\n");
  }
  const ReadReport& r = city.report;
  std::printf(
      "repaired:    %zu duplicate points, %zu ring orientations, %zu unclosed rings\n"
      "heights:     %zu from building:levels, %zu default, %zu LoD2 footprints from roofs\n",
      r.repaired_duplicate_points, r.repaired_orientation, r.repaired_unclosed, r.level_heights,
      r.default_heights, r.footprints_from_roof);
  // Thesis 7.1: where an occluder was kept smaller than the building, or none was made.
  std::printf(
      "cut:         %zu GeoJSON occluders cut to the eaves (roof:shape), %zu GeoJSON roofs as "
      "faces (roof:shape),\n"
      "             %zu roofs on open sides (building=roof) and %zu raised parts without "
      "occluder,\n"
      "             %zu footprints from walls under an overhanging roof, %zu parts without "
      "footprint,\n"
      "             %zu GroundSurfaces without walls round them\n"
      "terrain:     %zu GeoJSON objects set on the terrain; %zu installations merged into "
      "buildings\n",
      r.roof_eaves, r.roof_shapes, r.open_roofs, r.raised_parts, r.footprints_from_walls,
      r.footprints_unknown, r.grounds_off_walls, r.on_terrain, r.installations);
  if (!r.terrain_note.empty()) std::printf("DEM:         %s\n", r.terrain_note.c_str());
  if (r.osm_multipolygons > 0)
    std::printf("OSM:         %zu buildings from multipolygons\n", r.osm_multipolygons);
  std::printf("repairs:     %zu geometric repairs, %zu objects that occlude nothing\n",
              r.repairs.size(), r.non_occluding.size());
  for (const std::string& line : r.repairs) std::printf("  repaired: %s\n", line.c_str());
  for (const std::string& line : r.non_occluding) std::printf("  no occluder: %s\n", line.c_str());
  const Box3 b = city.bounds();
  LocalFrameMapping mapping(city.frame);
  const auto lo = mapping.to_input(b.xy.min.x, b.xy.min.y, b.zmin);
  const auto hi = mapping.to_input(b.xy.max.x, b.xy.max.y, b.zmax);
  std::printf("bbox:        %.3f %.3f %.3f .. %.3f %.3f %.3f (input coordinates)\n", lo[0], lo[1],
              lo[2], hi[0], hi[1], hi[2]);
  std::printf("extent:      %.1f m x %.1f m, z %.2f .. %.2f\n", b.xy.max.x - b.xy.min.x,
              b.xy.max.y - b.xy.min.y, b.zmin, b.zmax);
  std::sort(heights.begin(), heights.end());
  double sum = 0;
  for (double h : heights) sum += h;
  std::printf("height:      min %.2f, median %.2f, mean %.2f, max %.2f m above the object's base\n",
              heights.front(), heights[heights.size() / 2], sum / double(heights.size()),
              heights.back());
  std::size_t levels = 0;
  for (const Block& bl : blocks) levels += bl.levels.size();
  double occluder_area = 0;
  for (const Occluder& o : occluders) occluder_area += area(o.shape);
  std::printf("blocks:      %zu (%zu height levels)\n", blocks.size(), levels);
  std::printf("occluders:   %zu after shrinking by %.2f m; footprint area %.0f m2\n",
              occluders.size(), epsilon, footprint_area);
  std::printf("             (summed over levels: %.0f m2 of shrunk occluder)\n", occluder_area);
  for (std::size_t i = 0; i < r.warnings.size() && i < 10; ++i)
    std::printf("warning:     %s\n", r.warnings[i].c_str());
  if (r.warnings.size() > 10) std::printf("warning:     ... %zu more\n", r.warnings.size() - 10);
}

std::string svg_of(const City& city, const std::vector<Block>& blocks,
                   const std::vector<Occluder>& occluders) {
  SvgMap map(city.bounds().xy.grown(10));
  for (const CityObject& o : city.objects)
    for (const Polygon& p : o.footprint) map.polygon(p, "fill:#ddd;stroke:#888;stroke-width:0.5");
  for (const Block& b : blocks)
    for (const Polygon& p : b.levels.front().region)
      map.polygon(p, "fill:none;stroke:#036;stroke-width:1");
  for (const Occluder& o : occluders)
    map.polygon(o.shape, "fill:#c33;fill-opacity:0.15;stroke:none");
  return map.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Reads city models (CityJSON, CityGML, GeoJSON, OpenStreetMap, Shapefile, GeoPackage, "
      "FlatGeobuf) and reports objects, heights, "
      "blocks and shrunk occluders."};
  std::vector<std::string> files;
  ReadOptions read;
  BlockOptions block_options;
  ViewCellOptions cells;  // only its epsilon, the shrinking distance of the bake
  std::string svg;
  app.add_option("files", files, "City files")->required()->check(CLI::ExistingFile);
  // The reading and block options of the bake, from the stages' own tables.
  const SettingOptions<ReadOptions> read_options(app, read_settings());
  const SettingOptions<BlockOptions> block_setting_options(app, block_settings());
  const SettingTable<ViewCellOptions> epsilon_only = {
      *find_setting(view_cell_settings(), "epsilon")};
  const SettingOptions<ViewCellOptions> epsilon_option(app, epsilon_only);
  app.add_flag("--skip-invalid")
      ->description("Accepted for old scripts; buildings are now always kept");
  app.add_option("--svg", svg, "Write a map of footprints, blocks and occluders");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  }
  try {
    read_options.apply(read);
    block_setting_options.apply(block_options);
    epsilon_option.apply(cells);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "urbanpvs-cityinfo: %s\nRun with --help for more information.\n",
                 e.what());
    return kExitUsage;
  }
  const double epsilon = cells.epsilon;
  try {
    const City city = read_city(files, read);
    const std::vector<Block> blocks = build_blocks(city.objects, block_options);
    const std::vector<Occluder> occluders = shrink_blocks(blocks, epsilon);
    print_summary(city, blocks, occluders, epsilon);
    if (!svg.empty()) {
      try {
        urbanpvs::runtime::write_file_atomic(svg, svg_of(city, blocks, occluders));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "urbanpvs-cityinfo: %s\n", e.what());
        return kExitOutput;
      }
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "urbanpvs-cityinfo: %s\n", e.what());
    return exit_code(e.problem());
  } catch (const std::exception& e) {  // a failure of ours, not of the input: no abort
    std::fprintf(stderr, "urbanpvs-cityinfo: %s\n", e.what());
    return kExitProcessing;
  }
  return 0;
}
