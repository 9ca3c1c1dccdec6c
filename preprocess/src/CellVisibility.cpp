// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/CellVisibility.hpp"

#include <algorithm>

#include "urbanpvs/preprocess/CullMapHorizon.hpp"
#include "urbanpvs/preprocess/ObjectTest.hpp"

namespace urbanpvs::preprocess {
namespace {

bool meets(const Box2& a, const Box2& b) {
  return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y;
}

// The map of step `step` of the growth: a square around the cell, ×2 per side per step, cut to
// the scene's area. Up to `fine_map` pixels per side it uses the scene's pixel (the thesis's
// maps); beyond, the pixel doubles with the side and coverage becomes whole-pixel. Every map is
// a window of the lattice of its pixel size anchored at the area's origin, so the last one
// covers the whole area (and, with fine_map large enough, is exactly the brute-force map).
CullMapGrid window(const CullMapGrid& area, const Box2& cell, int initial_map, int fine_map,
                   int step, bool* last) {
  int fine_steps = 0;
  while ((initial_map << (fine_steps + 1)) <= fine_map) ++fine_steps;
  const int coarse = std::max(0, step - fine_steps);
  const double k = area.pixel * static_cast<double>(1 << std::min(coarse, 24));
  const long long side = static_cast<long long>(initial_map) << std::min(step - coarse, 24);
  const long long nw = static_cast<long long>(std::ceil(area.width * area.pixel / k - 1e-9));
  const long long nh = static_cast<long long>(std::ceil(area.height * area.pixel / k - 1e-9));
  const auto ci =
      static_cast<long long>(std::floor((0.5 * (cell.min.x + cell.max.x) - area.origin.x) / k));
  const auto cj =
      static_cast<long long>(std::floor((0.5 * (cell.min.y + cell.max.y) - area.origin.y) / k));
  const long long i0 = std::max(0LL, ci - side / 2), j0 = std::max(0LL, cj - side / 2);
  const long long i1 = std::min(nw, ci - side / 2 + side), j1 = std::min(nh, cj - side / 2 + side);
  CullMapGrid g;
  g.pixel = k;
  g.whole_pixel = coarse > 0;
  g.origin = {area.origin.x + static_cast<double>(i0) * k,
              area.origin.y + static_cast<double>(j0) * k};
  g.width = static_cast<int>(std::max(1LL, i1 - i0));
  g.height = static_cast<int>(std::max(1LL, j1 - j0));
  *last = i0 == 0 && j0 == 0 && i1 == nw && j1 == nh;
  return g;
}

}  // namespace

CellCounters& CellCounters::operator+=(const CellCounters& o) {
  cells += o.cells;
  maps += o.maps;
  map_pixels += o.map_pixels;
  largest_map = std::max(largest_map, o.largest_map);
  early_breaks += o.early_breaks;
  occluders_considered += o.occluders_considered;
  occluders_rendered += o.occluders_rendered;
  occluders_occluded += o.occluders_occluded;
  occluders_behind_horizon += o.occluders_behind_horizon;
  objects_in_map += o.objects_in_map;
  objects_behind_horizon += o.objects_behind_horizon;
  nodes_behind_horizon += o.nodes_behind_horizon;
  shadows += o.shadows;
  pixels_written += o.pixels_written;
  return *this;
}

CellVisibility::CellVisibility(const BakeScene& scene)
    : scene_(scene),
      renderer_(make_cell_map_renderer(scene.options().backend, scene.zlo(), scene.zhi())),
      all_occluders_(pointers_to(scene.occluders())),
      object_decided_(scene.city().objects.size(), 0),
      occluder_dropped_(scene.occluders().size(), 0),
      object_node_done_(scene.object_index().nodes().size(), 0),
      occluder_node_done_(scene.occluder_index().nodes().size(), 0),
      object_visible_(scene.city().objects.size(), 0) {}

CellVisibility::~CellVisibility() = default;

std::vector<std::uint32_t> CellVisibility::pvs(std::uint32_t cell, CellCounters* counters) {
  CellCounters local;
  CellCounters& c = counters ? *counters : local;
  ++c.cells;
  return scene_.options().method == Method::BruteForce ? brute_force(cell, c)
                                                       : hierarchical(cell, c);
}

std::vector<std::uint32_t> CellVisibility::brute_force(std::uint32_t cell, CellCounters& c) {
  const CullMapGrid& grid = scene_.area();
  const std::vector<Vec3> samples = scene_.samples(cell);
  const std::vector<const geometry::Occluder*>& all = all_occluders_;
  CullMapStats stats;
  const CullMap map = renderer_->render(grid, samples, all, &stats);
  ++c.maps;
  c.map_pixels += static_cast<std::uint64_t>(grid.width) * static_cast<std::uint64_t>(grid.height);
  c.largest_map = std::max<std::uint64_t>(
      c.largest_map, static_cast<std::uint64_t>(std::max(grid.width, grid.height)));
  c.occluders_considered += all.size();
  c.occluders_rendered += all.size();
  c.objects_in_map += scene_.city().objects.size();
  c.shadows += stats.shadows;
  c.pixels_written += stats.pixels_written;
  return visible_objects(map, scene_.city().objects);
}

std::vector<std::uint32_t> CellVisibility::hierarchical(std::uint32_t cell, CellCounters& c) {
  // A fresh stamp marks this cell's decisions; the arrays are only cleared when it wraps.
  if (++stamp_ == 0) {
    for (auto* v : {&object_decided_, &occluder_dropped_, &object_node_done_, &occluder_node_done_})
      std::fill(v->begin(), v->end(), 0u);
    stamp_ = 1;
  }
  const geometry::ViewCell& vc = scene_.mesh().cells[cell];
  CellBox box;
  for (const Vec2& p : vc.corner) box.xy.extend(p);
  box.top = vc.zmax;
  const std::vector<Vec3> samples = scene_.samples(cell);
  const auto& objects = scene_.city().objects;
  const BoxQuadtree& object_tree = scene_.object_index();
  const BoxQuadtree& occluder_tree = scene_.occluder_index();
  const CullMapGrid& area = scene_.area();

  std::vector<std::uint32_t> visible;
  std::vector<const geometry::Occluder*> render;
  std::optional<CullMap> previous;
  auto decide = [&](std::uint32_t object, bool is_visible) {
    object_decided_[object] = stamp_;
    if (is_visible) visible.push_back(object);
  };

  for (int step = 0;; ++step) {
    bool last = false;
    const CullMapGrid grid =
        window(area, box.xy, scene_.options().initial_map, scene_.options().fine_map, step, &last);
    if (!last && !inside_map(grid, box.xy.grown(area.pixel))) continue;  // cell larger than map
    const Box2 bounds = grid.bounds();

    // Occluders that meet this map and are not known to add nothing (thesis 5.6.1).
    render.clear();
    occluder_tree.visit(
        [&](std::uint32_t id, const BoxQuadtree::Node& n) {
          if (occluder_node_done_[id] == stamp_ || !meets(n.box.xy, bounds)) return false;
          if (previous && outside_map(previous->grid(), n.box.xy) &&
              hidden_behind_horizon(*previous, box, n.box)) {
            occluder_node_done_[id] = stamp_;
            ++c.nodes_behind_horizon;
            c.occluders_behind_horizon += n.total;
            return false;
          }
          return true;
        },
        [&](std::uint32_t o) {
          if (occluder_dropped_[o] == stamp_) return;
          const geometry::Box3& b = occluder_tree.box(o);
          if (!meets(b.xy, bounds)) return;
          ++c.occluders_considered;
          if (previous) {
            if (inside_map(previous->grid(), b.xy) && hidden_by(*previous, b)) {
              occluder_dropped_[o] = stamp_;
              ++c.occluders_occluded;
              return;
            }
            if (outside_map(previous->grid(), b.xy) && hidden_behind_horizon(*previous, box, b)) {
              occluder_dropped_[o] = stamp_;
              ++c.occluders_behind_horizon;
              return;
            }
          }
          render.push_back(&scene_.occluders()[o]);
        });
    // Quadtree order depends on geometry only; sorting by index keeps the rasterization order
    // (and so float ties) independent of it.
    std::sort(render.begin(), render.end());
    CullMapStats stats;
    CullMap map = renderer_->render(grid, samples, render, &stats);
    ++c.maps;
    c.map_pixels +=
        static_cast<std::uint64_t>(grid.width) * static_cast<std::uint64_t>(grid.height);
    c.largest_map = std::max<std::uint64_t>(
        c.largest_map, static_cast<std::uint64_t>(std::max(grid.width, grid.height)));
    c.occluders_rendered += render.size();
    c.shadows += stats.shadows;
    c.pixels_written += stats.pixels_written;

    // Objects: inside the map decided by its heights (final: nothing outside the map casts a
    // shadow into it), outside it by the horizon; the rest waits for a larger map.
    bool pending = false;
    object_tree.visit(
        [&](std::uint32_t id, const BoxQuadtree::Node& n) {
          if (object_node_done_[id] == stamp_) return false;
          if (!last && outside_map(grid, n.box.xy) && hidden_behind_horizon(map, box, n.box)) {
            object_node_done_[id] = stamp_;
            ++c.nodes_behind_horizon;
            object_tree.for_each_item_below(id, [&](std::uint32_t o) {
              if (object_decided_[o] == stamp_) return;
              decide(o, false);
              ++c.objects_behind_horizon;
            });
            return false;
          }
          return true;
        },
        [&](std::uint32_t o) {
          if (object_decided_[o] == stamp_) return;
          const geometry::Box3& b = objects[o].bbox;
          if (last || inside_map(grid, b.xy)) {
            decide(o, !hidden_by(map, b));
            ++c.objects_in_map;
          } else if (outside_map(grid, b.xy) && hidden_behind_horizon(map, box, b)) {
            decide(o, false);
            ++c.objects_behind_horizon;
          } else {
            pending = true;
          }
        });
    if (last) break;
    if (!pending) {
      ++c.early_breaks;
      break;
    }
    previous = std::move(map);
  }
  std::sort(visible.begin(), visible.end());
  return visible;
}

}  // namespace urbanpvs::preprocess
