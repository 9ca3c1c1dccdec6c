// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/FarField.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"
#include "urbanpvs/preprocess/visibility/SightLine.hpp"

namespace urbanpvs::preprocess {

FarField::FarField(const BakeScene& scene)
    : scene_(scene),
      far_visible_(scene.city().objects.size(), 0),
      far_open_(scene.city().objects.size(), 0) {}

std::vector<std::uint32_t> FarField::visible(std::span<const Vec3> samples,
                                             std::span<const std::uint32_t> objects_open,
                                             CellCounters& c) {
  // A fresh stamp marks this call's objects; the marks are only cleared when it wraps.
  if (++stamp_ == 0) {
    std::fill(far_open_.begin(), far_open_.end(), 0u);
    std::fill(far_visible_.begin(), far_visible_.end(), 0u);
    stamp_ = 1;
  }
  std::vector<std::uint32_t> found;
  // An object is met at its nearest distance; when its box is not hidden as a whole, again at
  // its farthest, when every wall in front of any of its pixel centres has been added.
  enum Kind : std::uint32_t { kNode, kOccluder, kObjectNode, kObject, kObjectCentres };
  // A min-heap; ties broken by kind and id so the sweep does not depend on the heap's layout.
  auto later = [](const Event& a, const Event& b) {
    return std::tie(a.distance, a.kind, a.id) > std::tie(b.distance, b.kind, b.id);
  };
  const auto& objects = scene_.city().objects;
  const std::vector<geometry::Ring>& outlines = scene_.object_outlines();
  const BoxQuadtree& tree = scene_.occluder_index();
  // The brute-force map decides an object by the centres of the pixels its outline touches
  // (thesis 7.2: with ε >= k·√2/2 a pixel centre speaks for the whole pixel). The horizons test
  // the box of the centres its box touches, every point of it, and where that fails the
  // outline's centres themselves: whatever they hide, that map hides.
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
    for (long long j = r.j0; j <= r.j1; ++j) {
      const PixelSpan row = outline_row(lattice, outlines[o], r, j);
      for (long long i = row.first; i <= row.last; ++i) {
        const Vec2 p = centre(i, j);
        if (h.hides_point(p, top)) continue;
        ++c.sight_lines;
        if (!sight_line_blocked(h.sample(), Vec3{p.x, p.y, top}, tree, scene_.occluders(),
                                kSightMargin))
          return false;
      }
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
    return {objects_open.begin(), objects_open.end()};
  }
  std::vector<Event>& heap = events_;
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
        found.push_back(e.id);
        --open;
      }
    }
  }
  return found;
}

}  // namespace urbanpvs::preprocess
