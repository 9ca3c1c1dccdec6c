// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

#include <algorithm>
#include <tuple>

#include "urbanpvs/preprocess/visibility/CullMapHorizon.hpp"
#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"
#include "urbanpvs/preprocess/visibility/SightLine.hpp"

namespace urbanpvs::preprocess {
namespace {

bool meets(const Box2& a, const Box2& b) {
  return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y;
}

// The map of step `step` of the growth: a square of initial_map << step pixels around the
// cell, cut to the scene's area; a window of the area's pixel lattice, so the last one (when
// maps may grow that far) is exactly the brute-force map.
CullMapGrid window(const CullMapGrid& area, const Box2& cell, long long side, bool* last) {
  const double k = area.pixel;
  const auto ci =
      static_cast<long long>(std::floor((0.5 * (cell.min.x + cell.max.x) - area.origin.x) / k));
  const auto cj =
      static_cast<long long>(std::floor((0.5 * (cell.min.y + cell.max.y) - area.origin.y) / k));
  const long long i0 = std::max(0LL, ci - side / 2), j0 = std::max(0LL, cj - side / 2);
  const long long i1 = std::min<long long>(area.width, ci - side / 2 + side);
  const long long j1 = std::min<long long>(area.height, cj - side / 2 + side);
  CullMapGrid g;
  g.pixel = k;
  g.origin = {area.origin.x + static_cast<double>(i0) * k,
              area.origin.y + static_cast<double>(j0) * k};
  g.width = static_cast<int>(std::max(1LL, i1 - i0));
  g.height = static_cast<int>(std::max(1LL, j1 - j0));
  *last = i0 == 0 && j0 == 0 && i1 == area.width && j1 == area.height;
  return g;
}

}  // namespace

CellVisibility::CellVisibility(const BakeScene& scene)
    : scene_(scene),
      // The brute-force reference draws the map of every occluder: skipping only those that
      // provably add nothing keeps it exactly that map, in a fraction of the time.
      renderer_(make_cell_map_renderer(scene.options().backend, scene.zlo(), scene.zhi(),
                                       scene.options().method == Method::Hierarchical
                                           ? OccluderSkipping::HiddenInMap
                                           : OccluderSkipping::BehindHorizon)),
      all_occluders_(pointers_to(scene.occluders())),
      object_decided_(scene.city().objects.size(), 0),
      occluder_dropped_(scene.occluders().size(), 0),
      occluder_node_done_(scene.occluder_index().nodes().size(), 0),
      far_field_(scene) {}

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
  return visible_objects(map, scene_.city().objects, scene_.object_outlines());
}

std::vector<std::uint32_t> CellVisibility::hierarchical(std::uint32_t cell, CellCounters& c) {
  // A fresh stamp marks this cell's decisions; the arrays are only cleared when it wraps.
  if (++stamp_ == 0) {
    for (auto* v : {&object_decided_, &occluder_dropped_, &occluder_node_done_})
      std::fill(v->begin(), v->end(), 0u);
    stamp_ = 1;
  }
  const geometry::ViewCell& vc = scene_.mesh().cells[cell];
  CellBox box;
  for (const Vec2& p : vc.corner) box.xy.extend(p);
  box.top = vc.zmax;
  const std::vector<Vec3> samples = scene_.samples(cell);
  const auto& objects = scene_.city().objects;
  const std::vector<geometry::Ring>& outlines = scene_.object_outlines();
  const BoxQuadtree& object_tree = scene_.object_index();
  const BoxQuadtree& occluder_tree = scene_.occluder_index();
  const CullMapGrid& area = scene_.area();

  std::vector<std::uint32_t> visible;
  // The objects the maps decided: few, near the cell. Every other object is left to a larger
  // map or to the far field, which takes them as "all but these", so that no step's work
  // grows with the size of the city.
  std::vector<std::uint32_t> decided;
  std::vector<const geometry::Occluder*> render;
  std::optional<CullMap> previous;
  auto decide = [&](std::uint32_t object, bool is_visible) {
    object_decided_[object] = stamp_;
    decided.push_back(object);
    if (is_visible) visible.push_back(object);
  };

  const BakeOptions& options = scene_.options();
  for (int step = 0;; ++step) {
    const long long side = static_cast<long long>(options.initial_map) << std::min(step, 24);
    if (side > options.max_map && previous) {
      // Beyond the largest map the sample horizons decide what is still open.
      for (std::uint32_t o : far_field_.visible_all_but(samples, decided, c)) visible.push_back(o);
      break;
    }
    bool last = false;
    const CullMapGrid grid = window(area, box.xy, side, &last);
    if (!last && !inside_map(grid, box.xy.grown(area.pixel))) continue;  // cell larger than map
    const Box2 bounds = grid.bounds();

    // Occluders that meet this map and are not known to add nothing (thesis 5.6.1).
    render.clear();
    bool sloped_left_out = false;
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
          // Occluders with sloped tops (roof faces, the terrain's squares) stay out of the
          // maps that are not the whole area. Every sample's map would rasterize the shadows
          // of all of them near the cell (several per building), and these small maps decide
          // few objects: the far field decides most. What such a map shows is left to the far
          // field, whose horizons and exact sight lines take in every sloped top; what it hides
          // without them is hidden with them.
          if (!last && scene_.occluders()[o].sloped()) {
            sloped_left_out = true;
            return;
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

    // Objects inside the map are decided by its heights (final: nothing outside the map casts a
    // shadow into it). The rest waits for a larger map or, beyond the largest, for the sample
    // horizons. (The map's own horizon, thesis 5.6, judges a sight line by the height at a
    // border pixel's centre, not where the line crosses the border: sound for the unshrunk
    // occluders by the ε argument of 7.2, but it can hide an object that the brute-force map,
    // judging every pixel centre exactly, shows. Objects are left to the sample horizons,
    // which never do; occluders it drops above only make the next map lower.)
    // Only nodes that meet the map (edges included) can hold an object inside it.
    object_tree.visit(
        [&](std::uint32_t, const BoxQuadtree::Node& n) {
          const Box2& b = n.box.xy;
          return last || (b.min.x <= bounds.max.x && bounds.min.x <= b.max.x &&
                          b.min.y <= bounds.max.y && bounds.min.y <= b.max.y);
        },
        [&](std::uint32_t o) {
          if (object_decided_[o] == stamp_) return;
          const geometry::Box3& b = objects[o].bbox;
          if (last || inside_map(grid, b.xy)) {
            const bool shown = !hidden_by(map, b, outlines[o]);
            ++c.objects_in_map;
            // Hidden without the sloped tops is hidden with them.
            if (!shown || !sloped_left_out) decide(o, shown);
          }
        });
    if (last) break;
    if (decided.size() == objects.size()) {
      ++c.early_breaks;
      break;
    }
    previous = std::move(map);
  }
  std::sort(visible.begin(), visible.end());
  return visible;
}

}  // namespace urbanpvs::preprocess
