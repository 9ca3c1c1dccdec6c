// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/CityBake.hpp"

#include <algorithm>

#include "urbanpvs/geometry/Occluder.hpp"
#include "urbanpvs/preprocess/CellCullMap.hpp"
#include "urbanpvs/preprocess/ObjectTest.hpp"
#include "urbanpvs/preprocess/OsMesaCullMapRenderer.hpp"

namespace urbanpvs::preprocess {
namespace {

runtime::Metadata metadata_of(const geometry::City& city, const BakeOptions& o) {
  runtime::Metadata m;
  m.frame.crs = city.frame.crs;
  m.frame.geographic = city.frame.kind == geometry::LocalFrame::Kind::Geographic;
  m.frame.geodetic_origin = {city.frame.origin_lat, city.frame.origin_lon, city.frame.origin_h};
  m.frame.origin = city.frame.origin;
  m.settings.epsilon_m = o.cells.epsilon;
  m.settings.pixel_size_m = o.pixel;
  m.settings.max_cell_edge_m = o.cells.max_cell_edge;
  m.settings.eye_min_m = o.cells.eye_min;
  m.settings.eye_max_m = o.cells.eye_max;
  m.properties.push_back({"gap_tolerance_m", std::to_string(o.blocks.gap_tolerance)});
  m.properties.push_back({"backend", o.backend == Backend::Cpu ? "cpu" : "osmesa"});
  return m;
}

// The samples of a cell: those of its three top edges (thesis 5.3).
std::vector<Vec3> cell_samples(const geometry::ViewCellMesh& mesh, const geometry::ViewCell& c) {
  std::vector<Vec3> out;
  for (std::uint32_t e : c.edge)
    for (const geometry::Point3& p : mesh.samples_of(mesh.edges[e])) out.push_back({p.x, p.y, p.z});
  return out;
}

}  // namespace

runtime::PvsBake bake_city(const geometry::City& city, const BakeOptions& options,
                           BakeStats* stats,
                           const std::function<void(std::size_t, std::size_t)>& progress) {
  CullMapSettings{options.cells.epsilon, options.pixel}.validate();
  const std::vector<geometry::Block> blocks = geometry::build_blocks(city.objects, options.blocks);
  const double shrink = options.shrink_override >= 0 ? options.shrink_override : options.cells.epsilon;
  const std::vector<geometry::Occluder> occluders = geometry::shrink_blocks(blocks, shrink);
  const geometry::ViewCellMesh mesh = geometry::build_view_cells(city, options.cells);

  geometry::Box2 area = mesh.bounds;
  area.extend(city.bounds().xy);
  const CullMapGrid grid = CullMapGrid::covering(area.grown(2 * options.pixel), options.pixel);
  const geometry::Box3 all = city.bounds();
  const double zlo = std::min(all.zmin, all.zmin - 1.0);
  const double zhi = all.zmax + 1000.0;

  runtime::PvsBake bake;
  bake.meta = metadata_of(city, options);
  for (const geometry::CityObject& o : city.objects)
    bake.objects.push_back({o.source_id, {o.bbox.xy.min.x, o.bbox.xy.min.y, o.bbox.zmin,
                                          o.bbox.xy.max.x, o.bbox.xy.max.y, o.bbox.zmax}});
  std::unique_ptr<OsMesaCullMapRenderer> gl;
  if (options.backend == Backend::OsMesa) gl = std::make_unique<OsMesaCullMapRenderer>();
  CullMapStats map_stats;
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
    const geometry::ViewCell& c = mesh.cells[i];
    const std::vector<Vec3> samples = cell_samples(mesh, c);
    const CullMap map = gl ? gl->cell_cull_map(grid, samples, occluders, zlo, zhi, &map_stats)
                           : cell_cull_map(grid, samples, occluders, &map_stats);
    runtime::CellRecord rec;
    // The runtime numbers neighbours by edge k = corner k -> k+1, the mesh by opposite corner.
    for (int k = 0; k < 3; ++k) {
      rec.triangle[k] = {c.corner[k].x, c.corner[k].y};
      const std::int32_t n = c.neighbour[(k + 2) % 3];
      rec.neighbours[k] = n < 0 ? runtime::kNoCell : static_cast<std::uint32_t>(n);
    }
    rec.z_min = c.zmin;
    rec.z_max = c.zmax;
    rec.pvs = visible_objects(map, city.objects);
    if (stats) stats->samples += samples.size(), stats->pvs_entries += rec.pvs.size();
    bake.cells.push_back(std::move(rec));
    if (progress) progress(i + 1, mesh.cells.size());
  }
  if (stats) {
    stats->blocks = blocks.size();
    stats->occluders = occluders.size();
    stats->cells = mesh.cells.size();
    stats->shadows = map_stats.shadows;
  }
  return bake;
}

}  // namespace urbanpvs::preprocess
