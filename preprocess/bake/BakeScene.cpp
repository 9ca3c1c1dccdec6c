// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeScene.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <string>

#include "urbanpvs/geometry/city/ObjectOutline.hpp"
#include "urbanpvs/geometry/occluders/InwardSimplification.hpp"
#include "urbanpvs/geometry/occluders/RoofPlaneOccluders.hpp"
#include "urbanpvs/geometry/occluders/SolidOccluders.hpp"
#include "urbanpvs/geometry/occluders/TerrainOccluders.hpp"
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

namespace urbanpvs::preprocess {
namespace {

// A building's solid takes TetGen milliseconds; one that takes this long has sent it into one
// of its endless loops (shrink_solids).
constexpr double kSecondsPerSolid = 10;  // [Units: s]

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
  return m;
}

std::vector<geometry::Box3> occluder_boxes(const std::vector<geometry::Occluder>& occluders) {
  std::vector<geometry::Box3> out;
  out.reserve(occluders.size());
  for (const geometry::Occluder& o : occluders) {
    geometry::Box3 b;
    b.xy = o.bounds;
    b.zmin = -std::numeric_limits<double>::infinity();  // prisms stand on the ground
    b.zmax = o.top_high();
    out.push_back(b);
  }
  return out;
}

std::vector<geometry::Box3> object_boxes(const std::vector<geometry::CityObject>& objects) {
  std::vector<geometry::Box3> out;
  out.reserve(objects.size());
  for (const geometry::CityObject& o : objects) out.push_back(o.bbox);
  return out;
}

}  // namespace

void BakeOptions::validate() const {
  // Every limit is the settings table's (BakeSettings.hpp), the one the command line enforces;
  // what is left here are the rules between settings.
  PreprocessRequest request;
  request.bake = *this;
  geometry::check_limits(bake_settings(), request);
  if (max_map < initial_map)
    throw std::invalid_argument("--max-map must be at least --initial-map (" +
                                std::to_string(initial_map) + "), got \"" +
                                std::to_string(max_map) + "\"");
  CullMapSettings{cells.epsilon, pixel}.validate();  // the coupling of ε and the pixel (7.2)
  geometry::validate(cells);                         // the region
  if (blocks.solid_step > 0 && !geometry::solid_shrinking_available())
    throw std::invalid_argument(
        "--solid-step needs TetGen: this build was configured with URBANPVS_TETGEN=OFF");
}

BakeScene::BakeScene(const geometry::City& city, const BakeOptions& options, unsigned threads)
    : city_(&city), options_(options) {
  // Walls closer than the block gap are one wall for the cells too: one setting, both stages.
  options_.cells.gap = options_.blocks.gap_tolerance;
  options_.validate();
  blocks_ = geometry::build_blocks(city.objects, options_.blocks);
  const double shrink =
      options_.shrink_override >= 0 ? options_.shrink_override : options_.cells.epsilon;
  occluders_ = geometry::shrink_blocks(blocks_, shrink);
  // The terrain under the objects hides what lies behind its crests (thesis 7.3.2); beyond
  // them it stands between no cell and no object.
  for (geometry::Occluder& o : geometry::terrain_occluders(city.terrain, city.bounds().xy,
                                                           options_.blocks.terrain_step, shrink))
    occluders_.push_back(std::move(o));
  if (const double side = options_.blocks.terrain_planes; side > 0) {
    terrain_squares_.first = static_cast<std::uint32_t>(occluders_.size());
    for (geometry::Occluder& o :
         geometry::terrain_plane_occluders(city.terrain, city.bounds().xy, side, shrink))
      occluders_.push_back(std::move(o));
    terrain_squares_.second = static_cast<std::uint32_t>(occluders_.size());
    terrain_pyramid_ = TerrainPyramid(
        std::span(occluders_)
            .subspan(terrain_squares_.first, terrain_squares_.second - terrain_squares_.first),
        side);
  }
  // Roof faces above the blocks' levels, with their slopes (thesis 4.2.1, 7.4): not fused, as a
  // face's plane holds only over its own ground.
  for (geometry::Occluder& o :
       geometry::roof_plane_occluders(city.objects, blocks_, shrink, options_.blocks, threads))
    occluders_.push_back(std::move(o));
  // Buildings that are not height fields keep, through the 3D route, what the blocks' prisms
  // cannot hold (thesis 7.3.1). Height fields are left to the blocks: fused with their
  // neighbours before they are eroded, they lose less than a building shrunk alone.
  if (options_.blocks.solid_step > 0) {
    std::vector<geometry::SolidInput> solids;
    for (const geometry::CityObject& object : city.objects)
      if (object.occludes && geometry::overhangs(object.surfaces, object.ground_z))
        solids.push_back({&object.surfaces, object.ground_z});
    for (geometry::ShrunkSolid& solid :
         geometry::shrink_solids(solids, shrink, options_.blocks.solid_step, kSecondsPerSolid)) {
      if (!solid.declined.empty()) ++solids_declined_[solid.declined];
      if (!solid.occluders.empty()) ++solids_shrunk_;
      for (geometry::Occluder& o : solid.occluders) occluders_.push_back(std::move(o));
    }
  }
  mesh_ = geometry::build_view_cells(city, options_.cells);

  // Two pixels of margin: every object's footprint and every cell lies strictly inside, so the
  // largest map decides everything.
  geometry::Box2 covered = mesh_.bounds;
  covered.extend(city.bounds().xy);
  area_ = CullMapGrid::covering(covered.grown(2 * options_.pixel), options_.pixel);
  const geometry::Box3 all = city.bounds();
  zlo_ = all.zmin - 1.0;
  for (const geometry::ViewCell& c : mesh_.cells) zlo_ = std::min(zlo_, c.zmin - 1.0);
  zhi_ = all.zmax + 1000.0;
  for (const geometry::Occluder& o : occluders_) zhi_ = std::max(zhi_, o.top_high() + 1000.0);
  object_index_ = BoxQuadtree(object_boxes(city.objects));
  object_outlines_.reserve(city.objects.size());
  for (const geometry::CityObject& o : city.objects)
    object_outlines_.push_back(geometry::object_outline(o));
  occluder_index_ = BoxQuadtree(occluder_boxes(occluders_));
  // Far outlines: the occluders with corners cut inwards, for the horizons (thesis 5.6) only;
  // the cull maps and the exact sight lines keep every wall.
  if (const double t = options_.far_outline_tolerance; t > 0) {
    far_outline_distance_ = BakeOptions::kFarOutlineRatio * t;
    far_occluders_.reserve(occluders_.size());
    for (const geometry::Occluder& o : occluders_) {
      // The same top (a part of an occluder under the same plane hides no more than the whole);
      // the outline's bounds still hold the far one.
      geometry::Occluder& far = far_occluders_.emplace_back(o);
      far.shape = geometry::simplified_inward(o.shape, t);
    }
  }
}

std::vector<Vec3> BakeScene::samples(std::uint32_t cell) const {
  std::vector<Vec3> out;
  for (std::uint32_t e : mesh_.cells[cell].edge) {
    // Two edges of a cell meet at each corner, and both end in a sample there: where the two
    // are the same point, it is taken once. A cell's map is the min over its samples and its far
    // field the union over them (thesis 5.5), so a second copy adds nothing but a second map and
    // sweep (an eighth of a cell's samples at the default edge length).
    for (const Vec3& s : mesh_.samples_of(mesh_.edges[e]))
      if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
  }
  return out;
}

runtime::CellRecord BakeScene::cell_record(std::uint32_t cell) const {
  const geometry::ViewCell& c = mesh_.cells[cell];
  runtime::CellRecord rec;
  // The runtime numbers neighbours by edge k = corner k -> k+1, the mesh by opposite corner.
  for (int k = 0; k < 3; ++k) {
    rec.triangle[static_cast<std::size_t>(k)] = {c.corner[static_cast<std::size_t>(k)].x,
                                                 c.corner[static_cast<std::size_t>(k)].y};
    const std::int32_t n = c.neighbour[static_cast<std::size_t>((k + 2) % 3)];
    rec.neighbours[static_cast<std::size_t>(k)] =
        n < 0 ? runtime::kNoCell : static_cast<std::uint32_t>(n);
  }
  rec.z_min = c.zmin;
  rec.z_max = c.zmax;
  return rec;
}

runtime::PvsBake BakeScene::pvs_file(std::vector<std::vector<std::uint32_t>> pvs,
                                     std::vector<std::pair<std::string, std::string>> properties,
                                     std::uint64_t input_hash) const {
  runtime::PvsBake bake = pvs_file_without_lists(pvs.size(), std::move(properties), input_hash);
  for (std::uint32_t c = 0; c < cell_count(); ++c) bake.cells[c].pvs = std::move(pvs[c]);
  return bake;
}

runtime::PvsBake BakeScene::pvs_file(const CompactPvsStore& pvs,
                                     std::vector<std::pair<std::string, std::string>> properties,
                                     std::uint64_t input_hash) const {
  runtime::PvsBake bake = pvs_file_without_lists(pvs.cells(), std::move(properties), input_hash);
  bake.pvs_source = [&pvs](std::uint32_t cell, std::vector<std::uint32_t>& out) {
    pvs.load(cell, out);
  };
  return bake;
}

runtime::PvsBake BakeScene::pvs_file_without_lists(
    std::size_t lists, std::vector<std::pair<std::string, std::string>> properties,
    std::uint64_t input_hash) const {
  if (lists != cell_count())
    throw std::invalid_argument("BakeScene::pvs_file: " + std::to_string(lists) + " PVSs for " +
                                std::to_string(cell_count()) + " cells");
  runtime::PvsBake bake;
  bake.meta = metadata_of(*city_, options_);
  bake.meta.settings.input_hash = input_hash;
  bake.meta.properties = std::move(properties);
  bake.objects.reserve(city_->objects.size());
  for (const geometry::CityObject& o : city_->objects)
    bake.objects.push_back({o.source_id,
                            {o.bbox.xy.min.x, o.bbox.xy.min.y, o.bbox.zmin, o.bbox.xy.max.x,
                             o.bbox.xy.max.y, o.bbox.zmax},
                            o.payload});
  bake.payload_key = city_->payload_key;
  bake.cells.reserve(cell_count());
  for (std::uint32_t c = 0; c < cell_count(); ++c) bake.cells.push_back(cell_record(c));
  return bake;
}

}  // namespace urbanpvs::preprocess
