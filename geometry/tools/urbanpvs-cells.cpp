// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-cells: subdivides a city's free space into view cells (thesis 5.3) and reports what
// came out: cell count, free area, edge lengths, angles, samples, time; optionally an SVG map of
// the cells over the footprints.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "urbanpvs/geometry/cells/SvgMap.hpp"
#include "urbanpvs/geometry/cells/ViewCellRegion.hpp"
#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"
#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/ReadSettings.hpp"
#include "urbanpvs/geometry/settings/SettingOptions.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/FileIo.hpp"

namespace {

using namespace urbanpvs::geometry;

constexpr int kExitUsage = urbanpvs::exit_code::kUsage;
constexpr int kExitProcessing = urbanpvs::exit_code::kProcessing;
constexpr int kExitOutput = urbanpvs::exit_code::kOutput;

void print_summary(const ViewCellMesh& m, double read_seconds) {
  double lmin = 1e300, lmax = 0, lsum = 0, amin = 180;
  std::size_t below = 0, samples = 0;
  for (const CellEdge& e : m.edges) {
    const Vec2 d = m.vertices[e.vertex[1]] - m.vertices[e.vertex[0]];
    const double l = std::hypot(d.x, d.y);
    lmin = std::min(lmin, l), lmax = std::max(lmax, l), lsum += l;
  }
  for (const ViewCell& c : m.cells) {
    const double a = min_angle_deg(c.corner);
    amin = std::min(amin, a);
    below += a < kMinCellAngleDeg;
    // The corners are shared by two of the cell's edges.
    for (std::uint32_t e : c.edge) samples += m.edges[e].sample_count - 1;
  }
  const double n = double(std::max<std::size_t>(1, m.cells.size()));
  const ViewCellOptions& o = m.options;
  std::printf("options:     max cell edge %.2f m, eye band %.2f..%.2f m, epsilon %.2f m\n",
              o.max_cell_edge, o.eye_min, o.eye_max, o.epsilon);
  std::printf("cells:       %zu (%zu vertices, %zu edges; %zu footprints subtracted)\n",
              m.cells.size(), m.vertices.size(), m.edges.size(), m.stats.footprints);
  std::printf("free space:  %.1f m2 in %.1f m x %.1f m\n", m.free_area,
              m.bounds.max.x - m.bounds.min.x, m.bounds.max.y - m.bounds.min.y);
  std::printf("edges:       min %.3f, mean %.3f, max %.3f m\n", lmin,
              lsum / double(std::max<std::size_t>(1, m.edges.size())), lmax);
  std::printf("angles:      min %.2f deg; %zu cells below %.1f deg (sharp input corners)\n", amin,
              below, kMinCellAngleDeg);
  std::printf("samples:     %zu in all, %.1f per cell\n", m.samples.size(), double(samples) / n);
  const char* ground = m.stats.ground == ViewCellStats::Ground::Terrain     ? "terrain"
                       : m.stats.ground == ViewCellStats::Ground::Buildings ? "building grounds"
                                                                            : "zero";
  std::printf("ground:      from %s; %zu rounded points moved off buildings\n", ground,
              m.stats.nudged_vertices);
  std::printf("slivers:     %zu left out (thinner than %.3f m along a wall), %.4f m2\n",
              m.stats.sliver_faces, o.narrow_gap, m.stats.sliver_area);
  std::printf("time:        read %.3f s, triangulate %.3f s, refine %.3f s, total %.3f s\n",
              read_seconds, m.stats.seconds_triangulation, m.stats.seconds_refinement,
              m.stats.seconds_total);
}

std::string svg_of(const City& city, const ViewCellMesh& m) {
  // The region the cells were asked for (pale blue: the streets with --cells streets), the
  // footprints (grey) and the cells over them (blue outlines).
  SvgMap map(m.bounds.grown(5));
  for (const Polygon& r : m.options.region)
    map.polygon(r, "fill:#dde8f4;stroke:#69c;stroke-width:0.5");
  for (const CityObject& o : city.objects)
    for (const Polygon& p : o.footprint) map.polygon(p, "fill:#bbb;stroke:none");
  std::vector<std::array<Vec2, 3>> cells;
  cells.reserve(m.cells.size());
  for (const ViewCell& c : m.cells) cells.push_back(c.corner);
  map.triangles(cells, "fill:none;stroke:#036;stroke-width:0.2");
  return map.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Subdivides a city's free space into view cells (constrained Delaunay "
      "triangulation, thesis 5.3) and reports them."};
  std::vector<std::string> files;
  ReadOptions read;
  ViewCellOptions options;
  std::string region, svg;
  app.add_option("files", files, "City files")->required()->check(CLI::ExistingFile);
  // The reading and view-cell options of the bake, from the stages' own tables.
  const SettingOptions<ReadOptions> read_options(app, read_settings());
  const SettingOptions<ViewCellOptions> cell_options(app, view_cell_settings());
  app.add_option("--region", region, "GeoJSON Polygon/MultiPolygon to subdivide (city's CRS)")
      ->check(CLI::ExistingFile);
  app.add_option("--svg", svg, "Write a map of the cells over the footprints");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  }
  try {
    read_options.apply(read);
    cell_options.apply(options);
    validate(options);
    if (options.placement == ViewCellOptions::Placement::File) {
      if (!region.empty())
        throw std::invalid_argument("--cells " + options.region_file + " and --region " + region +
                                    " both name a region: give one");
      region = options.region_file;
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "urbanpvs-cells: %s\n", e.what());
    return kExitUsage;
  }

  ViewCellMesh mesh;
  City city;
  try {
    const auto t0 = std::chrono::steady_clock::now();
    city = read_city(files, read);
    if (!region.empty()) options.region = read_region_file(region, city.frame);
    const double read_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    mesh = build_view_cells(city, options);
    print_summary(mesh, read_seconds);
  } catch (const InputError& e) {
    std::fprintf(stderr, "urbanpvs-cells: %s\n", e.what());
    return exit_code(e.problem());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "urbanpvs-cells: %s\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "urbanpvs-cells: %s\n", e.what());
    return kExitProcessing;
  }
  if (!svg.empty()) {
    try {
      urbanpvs::runtime::write_file_atomic(svg, svg_of(city, mesh));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "urbanpvs-cells: %s\n", e.what());
      return kExitOutput;
    }
  }
  return 0;
}
