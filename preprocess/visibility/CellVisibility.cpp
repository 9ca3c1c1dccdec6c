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
  nodes_behind_horizon += o.nodes_behind_horizon;
  objects_far_field += o.objects_far_field;
  occluders_far_field += o.occluders_far_field;
  sight_lines += o.sight_lines;
  shadows += o.shadows;
  pixels_written += o.pixels_written;
  return *this;
}

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
      far_visible_(scene.city().objects.size(), 0),
      far_open_(scene.city().objects.size(), 0) {}

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

// Objects the cull maps left open, decided per sample by a front-to-back sweep over the occluder
// quadtree with the sample's horizon (SampleHorizon): an object is hidden from the cell when it
// is hidden from every sample. Nodes and occluders already hidden are skipped whole; the sweep
// of a sample stops when every open object has been met.
void CellVisibility::far_field(std::span<const Vec3> samples,
                               std::span<const std::uint32_t> objects_open, CellCounters& c) {
  // An object is met at its nearest distance; when its box is not hidden as a whole, again at
  // its farthest, when every wall in front of any of its pixel centres has been added.
  enum Kind : std::uint32_t { kNode, kOccluder, kObjectNode, kObject, kObjectCentres };
  using Event = FarEvent;
  // A min-heap; ties broken by kind and id so the sweep does not depend on the heap's layout.
  auto later = [](const Event& a, const Event& b) {
    return std::tie(a.distance, a.kind, a.id) > std::tie(b.distance, b.kind, b.id);
  };
  const auto& objects = scene_.city().objects;
  const BoxQuadtree& tree = scene_.occluder_index();
  // The brute-force map decides an object by the centres of the pixels its box touches (thesis
  // 7.2: with ε >= k·√2/2 a pixel centre speaks for the whole pixel). The horizons test the box
  // through those centres, every point of it, and where that fails the centres themselves:
  // whatever they hide, that map hides.
  const CullMapGrid& lattice = scene_.area();
  auto centre = [&](long long i, long long j) {
    return lattice.center(static_cast<int>(i), static_cast<int>(j));
  };
  auto centres_box = [&](std::uint32_t o) {
    geometry::Box3 b = objects[o].bbox;
    const auto r = lattice.touched(b.xy);
    b.xy = {centre(r.i0, r.j0), centre(r.i1, r.j1)};
    return b;
  };
  // A centre the horizon's sectors leave open gets the exact sight line: the pixel's own test
  // in the brute-force map. The margin keeps float rounding of that map's heights (a few µm)
  // from making this one stricter.
  constexpr double kSightMargin = 1e-4;
  auto points_hidden = [&](const SampleHorizon& h, std::uint32_t o) {
    const double top = objects[o].bbox.zmax;
    const auto r = lattice.touched(objects[o].bbox.xy);
    for (long long j = r.j0; j <= r.j1; ++j)
      for (long long i = r.i0; i <= r.i1; ++i) {
        const Vec2 p = centre(i, j);
        if (h.hides_point(p, top)) continue;
        ++c.sight_lines;
        if (!sight_line_blocked(h.sample(), Vec3{p.x, p.y, top}, tree, scene_.occluders(),
                                kSightMargin))
          return false;
      }
    return true;
  };
  auto farthest = [&](const SampleHorizon& h, const geometry::Box2& b) {
    const double dx = std::max(h.sample().x - b.min.x, b.max.x - h.sample().x);
    const double dy = std::max(h.sample().y - b.min.y, b.max.y - h.sample().y);
    return std::hypot(dx, dy);
  };
  // Open objects per node of the object quadtree, so whole districts are tested at once.
  const BoxQuadtree& object_tree = scene_.object_index();
  for (std::uint32_t o : objects_open) far_open_[o] = stamp_;
  std::size_t open = objects_open.size();
  c.objects_far_field += open;
  const auto& nodes = object_tree.nodes();
  open_below_.assign(nodes.size(), 0);
  for (std::size_t id = nodes.size(); id-- > 0;) {  // children come after their parent
    const BoxQuadtree::Node& n = nodes[id];
    std::uint32_t count = 0;
    for (std::uint32_t k = 0; k < n.count; ++k)
      count += far_open_[object_tree.items()[n.first + k]] == stamp_ ? 1 : 0;
    for (std::int32_t child : n.child)
      if (child >= 0) count += open_below_[static_cast<std::size_t>(child)];
    open_below_[id] = count;
  }
  // A node's box holds its objects' boxes; grown by half a pixel it holds their centre boxes.
  auto node_box = [&](std::uint32_t id) {
    geometry::Box3 b = nodes[id].box;
    b.xy = b.xy.grown(0.5 * lattice.pixel * (1 + 1e-9));
    return b;
  };
  auto still_open = [&](std::uint32_t o) {
    return far_open_[o] == stamp_ && far_visible_[o] != stamp_;
  };

  // No occluder (every building may vanish when shrunk by ε, thesis 7.2): no wall casts a
  // shadow (thesis 4.2.1), so nothing is hidden from any sample and every open object is
  // visible; there is no quadtree root to start a sweep from. Likewise, should an object be
  // open with no object tree or no sample to sweep from, nothing proves it hidden.
  if (open > 0 && (tree.nodes().empty() || nodes.empty() || samples.empty())) {
    for (std::uint32_t o : objects_open) far_visible_[o] = stamp_;
    return;
  }
  std::vector<Event>& heap = far_events_;
  for (const Vec3& sample : samples) {
    if (open == 0) break;  // every open object is visible from some sample already
    SampleHorizon& h = horizon_;
    h.reset(sample);
    heap.clear();
    std::size_t object_events = 0;  // the sweep stops when no object is left to meet
    auto push = [&](double d, Kind kind, std::uint32_t id) {
      heap.push_back({d, kind, id});
      std::push_heap(heap.begin(), heap.end(), later);
      if (kind != kNode && kind != kOccluder) ++object_events;
    };
    push(h.distance_to(node_box(0).xy), kObjectNode, 0);
    push(h.distance_to(tree.nodes()[0].box.xy), kNode, 0);
    while (object_events > 0 && !heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const Event e = heap.back();
      heap.pop_back();
      if (e.kind != kNode && e.kind != kOccluder) --object_events;
      if (e.kind == kNode) {
        const BoxQuadtree::Node& n = tree.nodes()[e.id];
        if (h.hides(n.box)) continue;
        for (std::uint32_t k = 0; k < n.count; ++k) {
          const std::uint32_t o = tree.items()[n.first + k];
          push(h.distance_to(tree.box(o).xy), kOccluder, o);
        }
        for (std::int32_t child : n.child)
          if (child >= 0)
            push(h.distance_to(tree.nodes()[static_cast<std::size_t>(child)].box.xy), kNode,
                 static_cast<std::uint32_t>(child));
      } else if (e.kind == kOccluder) {
        if (h.hides(tree.box(e.id))) continue;
        h.add(scene_.occluders()[e.id]);
        ++c.occluders_far_field;
      } else if (e.kind == kObjectNode) {
        if (open_below_[e.id] == 0 || h.hides(node_box(e.id))) continue;
        const BoxQuadtree::Node& n = nodes[e.id];
        for (std::uint32_t k = 0; k < n.count; ++k) {
          const std::uint32_t o = object_tree.items()[n.first + k];
          if (still_open(o)) push(h.distance_to(centres_box(o).xy), kObject, o);
        }
        for (std::int32_t child : n.child)
          if (child >= 0 && open_below_[static_cast<std::size_t>(child)] > 0)
            push(h.distance_to(node_box(static_cast<std::uint32_t>(child)).xy), kObjectNode,
                 static_cast<std::uint32_t>(child));
      } else if (e.kind == kObject) {
        const geometry::Box3 b = centres_box(e.id);
        if (!h.hides(b)) push(farthest(h, b.xy), kObjectCentres, e.id);
      } else if (!points_hidden(h, e.id)) {
        far_visible_[e.id] = stamp_;
        --open;
      }
    }
  }
}

std::vector<std::uint32_t> CellVisibility::hierarchical(std::uint32_t cell, CellCounters& c) {
  // A fresh stamp marks this cell's decisions; the arrays are only cleared when it wraps.
  if (++stamp_ == 0) {
    for (auto* v :
         {&object_decided_, &occluder_dropped_, &occluder_node_done_, &far_visible_, &far_open_})
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
  std::vector<std::uint32_t> pending;
  std::vector<const geometry::Occluder*> render;
  std::optional<CullMap> previous;
  auto decide = [&](std::uint32_t object, bool is_visible) {
    object_decided_[object] = stamp_;
    if (is_visible) visible.push_back(object);
  };

  const BakeOptions& options = scene_.options();
  for (int step = 0;; ++step) {
    const long long side = static_cast<long long>(options.initial_map) << std::min(step, 24);
    if (side > options.max_map && previous) {
      // Beyond the largest map the sample horizons decide what is still open.
      far_field(samples, pending, c);
      for (std::uint32_t o : pending) decide(o, far_visible_[o] == stamp_);
      break;
    }
    bool last = false;
    const CullMapGrid grid = window(area, box.xy, side, &last);
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

    // Objects inside the map are decided by its heights (final: nothing outside the map casts a
    // shadow into it). The rest waits for a larger map or, beyond the largest, for the sample
    // horizons. (The map's own horizon, thesis 5.6, judges a sight line by the height at a
    // border pixel's centre, not where the line crosses the border: sound for the unshrunk
    // occluders by the ε argument of 7.2, but it can hide an object that the brute-force map,
    // judging every pixel centre exactly, shows. Objects are left to the sample horizons,
    // which never do; occluders it drops above only make the next map lower.)
    pending.clear();
    object_tree.visit([](std::uint32_t, const BoxQuadtree::Node&) { return true; },
                      [&](std::uint32_t o) {
                        if (object_decided_[o] == stamp_) return;
                        const geometry::Box3& b = objects[o].bbox;
                        if (last || inside_map(grid, b.xy)) {
                          decide(o, !hidden_by(map, b));
                          ++c.objects_in_map;
                        } else {
                          pending.push_back(o);
                        }
                      });
    if (last) break;
    if (pending.empty()) {
      ++c.early_breaks;
      break;
    }
    previous = std::move(map);
  }
  std::sort(visible.begin(), visible.end());
  return visible;
}

}  // namespace urbanpvs::preprocess
