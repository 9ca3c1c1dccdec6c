// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/FarField.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"
#include "urbanpvs/preprocess/visibility/SightLine.hpp"

namespace urbanpvs::preprocess {

namespace {

bool bit(const std::vector<std::uint64_t>& bits, std::uint32_t k) {
  return (bits[k >> 6] >> (k & 63)) & 1u;
}

void set_bit(std::vector<std::uint64_t>& bits, std::uint32_t k) {
  bits[k >> 6] |= std::uint64_t{1} << (k & 63);
}

// A sloped top that rises at least this much per metre (14°): a pitched roof face, a hillside;
// not the drainage fall of a flat roof, whose walls all stand about as high as its top.
// Such tops stay out of the horizons. Rising away from a sample, a face shows it mostly its low
// side: its walls that face the sample are eaves, which the block's level below holds too (its
// prism is cut at the lowest roof point, thesis 7.3.2). Falling away, its near wall is a ridge,
// and that hides much behind a pitched roof, but so does the exact sight line (points_hidden),
// and on pitched roofs the walls of every face cost the sweeps more than tracing what only the
// faces hide. Nearly flat faces (real LoD2.2 roofs have many) are kept: they hide like levels.
// The PVS does not depend on the horizon: a pixel centre that it leaves open is traced exactly
// past every occluder, faces included, so a lower horizon costs sight lines, never hidden
// objects (README, "Steep sloped tops stay out of the horizons").
constexpr double kSteepTop = 0.25;

// Wraps a stamp; clears the marks it stamps when it comes round to 0.
void next_stamp(std::uint32_t& stamp, std::initializer_list<std::vector<std::uint32_t>*> marks) {
  if (++stamp != 0) return;
  for (auto* m : marks) std::fill(m->begin(), m->end(), 0u);
  stamp = 1;
}

}  // namespace

FarField::FarField(const BakeScene& scene, std::size_t kept_samples, HorizonTops tops)
    : scene_(scene),
      far_visible_(scene.city().objects.size(), 0),
      asked_(scene.city().objects.size(), 0),
      seen_in_sweep_(scene.city().objects.size(), 0) {
  const std::size_t words = (scene.city().objects.size() + 63) / 64;
  const std::size_t bytes = std::max<std::size_t>(1, 2 * words * sizeof(std::uint64_t));
  answers_.resize(std::min(kept_samples, kKeptBytes / bytes));
  for (SampleAnswers& a : answers_) {
    a.asked.assign(words, 0);
    a.seen.assign(words, 0);
  }
  std::vector<geometry::Box3> horizon_boxes;
  for (std::uint32_t o = 0; o < scene.occluders().size(); ++o) {
    const Vec2 slope = scene.occluders()[o].slope;
    if (tops == HorizonTops::AllButSteep && std::hypot(slope.x, slope.y) >= kSteepTop) continue;
    horizon_ids_.push_back(o);
    horizon_boxes.push_back(scene.occluder_index().box(o));
  }
  horizon_tree_ = BoxQuadtree(horizon_boxes);
  const BoxQuadtree& tree = scene.object_index();
  const auto& nodes = tree.nodes();
  parent_.assign(nodes.size(), -1);
  node_of_.assign(scene.city().objects.size(), -1);
  std::vector<std::uint32_t> depth(nodes.size(), 1);
  for (std::size_t id = 0; id < nodes.size(); ++id) {  // children come after their parent
    const BoxQuadtree::Node& n = nodes[id];
    for (std::uint32_t k = 0; k < n.count; ++k)
      node_of_[tree.items()[n.first + k]] = static_cast<std::int32_t>(id);
    for (std::int32_t child : n.child)
      if (child >= 0) {
        parent_[static_cast<std::size_t>(child)] = static_cast<std::int32_t>(id);
        depth[static_cast<std::size_t>(child)] = depth[id] + 1;
      }
    depth_ = std::max(depth_, depth[id]);
  }
}

void FarField::count_asked(std::span<const std::uint32_t> ask,
                           std::span<const std::uint32_t> not_asked) {
  const BoxQuadtree& tree = scene_.object_index();
  const auto& nodes = tree.nodes();
  // Counted afresh: every node and item once.
  auto count = [&](std::vector<std::uint32_t>& out) {
    out.assign(nodes.size(), 0);
    for (std::size_t id = nodes.size(); id-- > 0;) {  // children come after their parent
      const BoxQuadtree::Node& n = nodes[id];
      std::uint32_t c = 0;
      for (std::uint32_t k = 0; k < n.count; ++k)
        c += asked_[tree.items()[n.first + k]] == sweep_stamp_ ? 1 : 0;
      for (std::int32_t child : n.child)
        if (child >= 0) c += out[static_cast<std::size_t>(child)];
      out[id] = c;
    }
  };
  // A new sweep: `ask` (and `also`) are the objects asked in it, nothing is seen yet.
  auto begin_sweep = [&](std::span<const std::uint32_t> also) {
    next_stamp(sweep_stamp_, {&asked_, &seen_in_sweep_});
    for (std::uint32_t o : ask) asked_[o] = sweep_stamp_;
    for (std::uint32_t o : also) asked_[o] = sweep_stamp_;
  };
  if (not_asked.size() * depth_ >= nodes.size() + tree.items().size()) {
    begin_sweep({});
    count(open_below_);
    return;
  }
  if (call_counted_ != calls_) {  // the open objects are `ask` and `not_asked` together
    begin_sweep(not_asked);
    count(open_in_call_);
    call_counted_ = calls_;
  }
  open_below_ = open_in_call_;
  for (std::uint32_t o : not_asked)
    for (std::int32_t id = node_of_[o]; id >= 0; id = parent_[static_cast<std::size_t>(id)])
      --open_below_[static_cast<std::size_t>(id)];
  begin_sweep({});
}

FarField::SampleAnswers* FarField::kept(const Vec3& sample) {
  for (SampleAnswers& a : answers_)
    if (a.last_used != 0 && a.sample == sample) {
      a.last_used = calls_;
      return &a;
    }
  return nullptr;
}

FarField::SampleAnswers* FarField::keep(const Vec3& sample) {
  // The least recently read; never one this call reads (its pointer is in known_).
  SampleAnswers* slot = nullptr;
  for (SampleAnswers& a : answers_)
    if (a.last_used != calls_ && (!slot || a.last_used < slot->last_used)) slot = &a;
  if (!slot) return nullptr;
  slot->sample = sample;
  slot->last_used = calls_;
  std::fill(slot->asked.begin(), slot->asked.end(), 0);
  std::fill(slot->seen.begin(), slot->seen.end(), 0);
  return slot;
}

std::vector<std::uint32_t> FarField::visible(std::span<const Vec3> samples,
                                             std::span<const std::uint32_t> objects_open,
                                             CellCounters& c) {
  next_stamp(stamp_, {&far_visible_});
  ++calls_;
  std::vector<std::uint32_t> found;
  std::size_t open = objects_open.size();
  c.objects_far_field += open;
  // No occluder (every building may vanish when shrunk by ε, thesis 7.2): no wall casts a
  // shadow (thesis 4.2.1), so nothing is hidden from any sample and every open object is
  // visible; there is no quadtree root to start a sweep from. Likewise, should an object be
  // open with no object tree or no sample to sweep from, nothing proves it hidden.
  if (open > 0 && (scene_.occluder_index().nodes().empty() ||
                   scene_.object_index().nodes().empty() || samples.empty())) {
    return {objects_open.begin(), objects_open.end()};
  }
  auto mark_visible = [&](std::uint32_t o) {
    if (far_visible_[o] == stamp_) return;
    far_visible_[o] = stamp_;
    found.push_back(o);
    --open;
  };
  // What kept samples are known to see is visible from the cell: the union over samples.
  known_.clear();
  for (const Vec3& s : samples) known_.push_back(kept(s));
  for (const SampleAnswers* a : known_)
    if (a)
      for (std::uint32_t o : objects_open)
        if (bit(a->seen, o)) mark_visible(o);
  // Each sample is asked what is still open and it has not answered yet; a sample that
  // answered all of that needs no sweep.
  // Samples with nothing kept first: they must be swept anyway, and what they see is then no
  // longer asked of the kept ones, which often spares those a sweep.
  order_.clear();
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (!known_[i]) order_.push_back(i);
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (known_[i]) order_.push_back(i);
  for (std::size_t i : order_) {
    if (open == 0) break;
    SampleAnswers* a = known_[i];
    ask_.clear();
    not_asked_.clear();
    for (std::uint32_t o : objects_open)
      (far_visible_[o] != stamp_ && !(a && bit(a->asked, o)) ? ask_ : not_asked_).push_back(o);
    if (ask_.empty()) {
      ++c.sweeps_spared;
      continue;
    }
    if (!a) a = known_[i] = keep(samples[i]);
    seen_.clear();
    sweep(samples[i], ask_, not_asked_, c, seen_);
    if (a) {
      for (std::uint32_t o : ask_) set_bit(a->asked, o);
      for (std::uint32_t o : seen_) set_bit(a->seen, o);
    }
    for (std::uint32_t o : seen_) mark_visible(o);
  }
  return found;
}

void FarField::sweep(const Vec3& sample, std::span<const std::uint32_t> ask,
                     std::span<const std::uint32_t> not_asked, CellCounters& c,
                     std::vector<std::uint32_t>& seen) {
  count_asked(ask, not_asked);
  ++c.sample_sweeps;
  // An object is met at its nearest distance; when its box is not hidden as a whole, again at
  // its farthest, when every wall in front of any of its pixel centres has been added.
  enum Kind : std::uint32_t { kNode, kOccluder, kObjectNode, kObject, kObjectCentres };
  // A min-heap; ties broken by kind and id so the sweep does not depend on the heap's layout.
  auto later = [](const Event& a, const Event& b) {
    return std::tie(a.distance, a.kind, a.id) > std::tie(b.distance, b.kind, b.id);
  };
  const auto& objects = scene_.city().objects;
  const std::vector<geometry::Ring>& outlines = scene_.object_outlines();
  const BoxQuadtree& tree = scene_.occluder_index();  // every occluder, for the sight lines
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
  // The occluder that blocked this sample's last sight line, asked first by the next one.
  std::uint32_t blocker = std::numeric_limits<std::uint32_t>::max();
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
                                kSightMargin, &blocker))
          return false;
      }
    }
    return true;
  };
  auto farthest = [&](const SampleHorizon& h, const geometry::Box2& b) {
    const double dx = std::max(h.sample().x - b.min.x, b.max.x - h.sample().x);
    const double dy = std::max(h.sample().y - b.min.y, b.max.y - h.sample().y);
    return ground_length(dx, dy);
  };
  // Asked objects per node of the object quadtree, so whole districts are tested at once.
  const BoxQuadtree& object_tree = scene_.object_index();
  const auto& nodes = object_tree.nodes();
  // A node's box holds its objects' boxes; grown by half a pixel it holds their centre boxes.
  auto node_box = [&](std::uint32_t id) {
    geometry::Box3 b = nodes[id].box;
    b.xy = b.xy.grown(0.5 * lattice.pixel * (1 + 1e-9));
    return b;
  };
  auto still_open = [&](std::uint32_t o) {
    return asked_[o] == sweep_stamp_ && seen_in_sweep_[o] != sweep_stamp_;
  };

  std::vector<Event>& heap = events_;
  {
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
    if (!horizon_tree_.nodes().empty())
      push(h.distance_to(horizon_tree_.nodes()[0].box.xy), kNode, 0);
    while (object_events > 0 && !heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const Event e = heap.back();
      heap.pop_back();
      if (e.kind != kNode && e.kind != kOccluder) --object_events;
      if (e.kind == kNode) {
        const BoxQuadtree::Node& n = horizon_tree_.nodes()[e.id];
        if (h.hides(n.box)) continue;
        for (std::uint32_t k = 0; k < n.count; ++k) {
          const std::uint32_t o = horizon_tree_.items()[n.first + k];
          push(h.distance_to(horizon_tree_.box(o).xy), kOccluder, o);
        }
        for (std::int32_t child : n.child)
          if (child >= 0)
            push(h.distance_to(horizon_tree_.nodes()[static_cast<std::size_t>(child)].box.xy),
                 kNode, static_cast<std::uint32_t>(child));
      } else if (e.kind == kOccluder) {
        if (h.hides(horizon_tree_.box(e.id))) continue;
        h.add(scene_.horizon_occluder(horizon_ids_[e.id], e.distance));
        ++c.occluders_far_field;
      } else if (e.kind == kObjectNode) {
        if (open_below_[e.id] == 0 || h.hides_as_is(node_box(e.id))) continue;
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
        if (!h.hides_as_is(b)) push(farthest(h, b.xy), kObjectCentres, e.id);
      } else if (!points_hidden(h, e.id)) {
        seen_in_sweep_[e.id] = sweep_stamp_;
        seen.push_back(e.id);
      }
    }
  }
}

}  // namespace urbanpvs::preprocess
