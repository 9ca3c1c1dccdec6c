// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/FarField.hpp"

#include <algorithm>
#include <bit>
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

// Calls f(k) for every bit k set in `word` number w.
template <class F>
void for_each_bit(std::uint64_t word, std::size_t w, F&& f) {
  while (word != 0) {
    f(static_cast<std::uint32_t>(w * 64 + static_cast<std::size_t>(std::countr_zero(word))));
    word &= word - 1;
  }
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

// A sweep asked about at most this many objects watches only their sectors. Building the
// watch costs a box view per object; a sample asked about every open object (thousands) would
// watch nearly all round anyway.
constexpr std::size_t kWatchedAsk = 256;

// Wraps a stamp; clears the marks it stamps when it comes round to 0.
void next_stamp(std::uint32_t& stamp, std::initializer_list<std::vector<std::uint32_t>*> marks) {
  if (++stamp != 0) return;
  for (auto* m : marks) std::fill(m->begin(), m->end(), 0u);
  stamp = 1;
}

}  // namespace

FarField::FarField(const BakeScene& scene, std::size_t kept_samples, HorizonTops tops,
                   TerrainHorizon terrain, SweepWatch watch)
    : scene_(scene),
      terrain_(terrain == TerrainHorizon::Pyramid ? &scene.terrain_pyramid() : nullptr),
      watch_(watch),
      seen_in_sweep_(scene.city().objects.size(), 0) {
  const std::size_t objects = scene.city().objects.size();
  const std::size_t words = (objects + 63) / 64;
  const std::size_t bytes = std::max<std::size_t>(1, 2 * words * sizeof(std::uint64_t));
  answers_.resize(std::min(kept_samples, kKeptBytes / bytes));
  // Every slot free, in one list from the oldest (slot 0) to the newest.
  for (std::uint32_t k = 0; k < answers_.size(); ++k) {
    SampleAnswers& a = answers_[k];
    a.asked.assign(words, 0);
    a.seen.assign(words, 0);
    a.older = k == 0 ? kNoSlot : k - 1;
    a.newer = k + 1 == answers_.size() ? kNoSlot : k + 1;
  }
  if (!answers_.empty()) {
    oldest_ = 0;
    newest_ = static_cast<std::uint32_t>(answers_.size() - 1);
  }
  slot_of_.reserve(answers_.size());
  open_.assign(words, 0);
  found_.assign(words, 0);
  ask_.assign(words, 0);
  std::vector<geometry::Box3> horizon_boxes;
  for (std::uint32_t o = 0; o < scene.occluders().size(); ++o) {
    if (terrain_ && scene.is_terrain_square(o)) continue;  // taken from the pyramid
    const Vec2 slope = scene.occluders()[o].slope;
    if (tops == HorizonTops::AllButSteep && std::hypot(slope.x, slope.y) >= kSteepTop) continue;
    horizon_ids_.push_back(o);
    horizon_boxes.push_back(scene.occluder_index().box(o));
  }
  horizon_tree_ = BoxQuadtree(horizon_boxes);
  // Bits in depth-first order of the object quadtree: a node's items, then its children's.
  // Objects the tree does not hold (none are met by a sweep) take the bits after its runs.
  const BoxQuadtree& tree = scene.object_index();
  const auto& nodes = tree.nodes();
  constexpr std::uint32_t kNone = 0xffffffffu;
  position_.assign(objects, kNone);
  run_.assign(nodes.size(), {});
  std::uint32_t next = 0;
  std::vector<std::pair<std::uint32_t, bool>> stack;  // node, and whether its children are done
  if (!nodes.empty()) stack.push_back({0, false});
  while (!stack.empty()) {
    auto [id, done] = stack.back();
    stack.pop_back();
    const BoxQuadtree::Node& n = nodes[id];
    if (done) {
      run_[id].end = next;
      continue;
    }
    run_[id].begin = next;
    for (std::uint32_t k = 0; k < n.count; ++k) position_[tree.items()[n.first + k]] = next++;
    stack.push_back({id, true});
    for (int c = 3; c >= 0; --c)
      if (n.child[c] >= 0) stack.push_back({static_cast<std::uint32_t>(n.child[c]), false});
  }
  for (std::uint32_t& p : position_)
    if (p == kNone) p = next++;
  object_at_.assign(objects, 0);
  for (std::uint32_t o = 0; o < objects; ++o) object_at_[position_[o]] = o;
}

bool FarField::any_asked(Run run) const {
  if (run.begin >= run.end) return false;
  const std::uint32_t first = run.begin >> 6, last = (run.end - 1) >> 6;
  const std::uint64_t head = ~std::uint64_t{0} << (run.begin & 63);
  const std::uint64_t tail = ~std::uint64_t{0} >> (63 - ((run.end - 1) & 63));
  if (first == last) return (ask_[first] & head & tail) != 0;
  if ((ask_[first] & head) != 0 || (ask_[last] & tail) != 0) return true;
  for (std::uint32_t w = first + 1; w < last; ++w)
    if (ask_[w] != 0) return true;
  return false;
}

std::size_t FarField::SampleKeyHash::operator()(const SampleKey& k) const noexcept {
  // The three words mixed by odd multipliers (splitmix64's), then folded.
  std::uint64_t h = k.x * 0x9e3779b97f4a7c15ull;
  h ^= (k.y + (h >> 29)) * 0xbf58476d1ce4e5b9ull;
  h ^= (k.z + (h >> 31)) * 0x94d049bb133111ebull;
  return static_cast<std::size_t>(h ^ (h >> 32));
}

FarField::SampleKey FarField::key_of(const Vec3& s) {
  return {std::bit_cast<std::uint64_t>(s.x), std::bit_cast<std::uint64_t>(s.y),
          std::bit_cast<std::uint64_t>(s.z)};
}

void FarField::touch(std::uint32_t k) {
  if (k == newest_) return;
  SampleAnswers& a = answers_[k];
  // Unlink (k is not the newest, so a.newer is a slot)...
  answers_[a.newer].older = a.older;
  if (a.older != kNoSlot)
    answers_[a.older].newer = a.newer;
  else
    oldest_ = a.newer;
  // ...and link at the newest end.
  a.older = newest_;
  a.newer = kNoSlot;
  answers_[newest_].newer = k;
  newest_ = k;
}

FarField::SampleAnswers* FarField::kept(const Vec3& sample) {
  const auto it = slot_of_.find(key_of(sample));
  if (it == slot_of_.end()) return nullptr;
  answers_[it->second].last_used = calls_;
  touch(it->second);
  return &answers_[it->second];
}

FarField::SampleAnswers* FarField::keep(const Vec3& sample) {
  // The least recently read; never one this call reads (its pointer is in known_). Slots read
  // by this call are the newest, so when the oldest is one of them, all are.
  if (oldest_ == kNoSlot || answers_[oldest_].last_used == calls_) return nullptr;
  const std::uint32_t k = oldest_;
  SampleAnswers& slot = answers_[k];
  if (slot.last_used != 0) slot_of_.erase(key_of(slot.sample));
  slot.sample = sample;
  slot.last_used = calls_;
  std::fill(slot.asked.begin(), slot.asked.end(), 0);
  std::fill(slot.seen.begin(), slot.seen.end(), 0);
  slot_of_[key_of(sample)] = k;
  touch(k);
  return &slot;
}

std::vector<std::uint32_t> FarField::visible(std::span<const Vec3> samples,
                                             std::span<const std::uint32_t> open, CellCounters& c) {
  std::fill(open_.begin(), open_.end(), 0);
  for (std::uint32_t o : open) set_bit(open_, position_[o]);
  return visible_open(samples, c);
}

std::vector<std::uint32_t> FarField::visible_all_but(std::span<const Vec3> samples,
                                                     std::span<const std::uint32_t> decided,
                                                     CellCounters& c) {
  const std::size_t objects = position_.size();
  std::fill(open_.begin(), open_.end(), ~std::uint64_t{0});
  if (objects % 64 != 0) open_.back() = (std::uint64_t{1} << (objects % 64)) - 1;
  for (std::uint32_t o : decided)
    open_[position_[o] >> 6] &= ~(std::uint64_t{1} << (position_[o] & 63));
  return visible_open(samples, c);
}

std::vector<std::uint32_t> FarField::visible_open(std::span<const Vec3> samples, CellCounters& c) {
  ++calls_;
  std::vector<std::uint32_t> found;
  std::size_t open = 0;
  for (std::uint64_t w : open_) open += static_cast<std::size_t>(std::popcount(w));
  c.objects_far_field += open;
  // No occluder (every building may vanish when shrunk by ε, thesis 7.2): no wall casts a
  // shadow (thesis 4.2.1), so nothing is hidden from any sample and every open object is
  // visible; there is no quadtree root to start a sweep from. Likewise, should an object be
  // open with no object tree or no sample to sweep from, nothing proves it hidden.
  if (open > 0 && (scene_.occluder_index().nodes().empty() ||
                   scene_.object_index().nodes().empty() || samples.empty())) {
    for (std::size_t w = 0; w < open_.size(); ++w)
      for_each_bit(open_[w], w, [&](std::uint32_t k) { found.push_back(object_at_[k]); });
    return found;
  }
  std::fill(found_.begin(), found_.end(), 0);
  auto mark_visible = [&](std::uint32_t k) {  // by bit
    found_[k >> 6] |= std::uint64_t{1} << (k & 63);
    found.push_back(object_at_[k]);
    --open;
  };
  // What kept samples are known to see is visible from the cell: the union over samples.
  known_.clear();
  for (const Vec3& s : samples) known_.push_back(kept(s));
  for (const SampleAnswers* a : known_)
    if (a)
      for (std::size_t w = 0; w < open_.size(); ++w)
        for_each_bit(a->seen[w] & open_[w] & ~found_[w], w, mark_visible);
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
    std::uint64_t any = 0;
    for (std::size_t w = 0; w < open_.size(); ++w) {
      ask_[w] = open_[w] & ~found_[w] & (a ? ~a->asked[w] : ~std::uint64_t{0});
      any |= ask_[w];
    }
    if (any == 0) {
      ++c.sweeps_spared;
      continue;
    }
    if (!a) a = known_[i] = keep(samples[i]);
    seen_.clear();
    sweep(samples[i], c, seen_);
    if (a) {
      for (std::size_t w = 0; w < open_.size(); ++w) a->asked[w] |= ask_[w];
      for (std::uint32_t o : seen_) set_bit(a->seen, position_[o]);
    }
    for (std::uint32_t o : seen_)
      if (!bit(found_, position_[o])) mark_visible(position_[o]);
  }
  return found;
}

void FarField::sweep(const Vec3& sample, CellCounters& c, std::vector<std::uint32_t>& seen) {
  next_stamp(sweep_stamp_, {&seen_in_sweep_});
  ++c.sample_sweeps;
  // An object is met at its nearest distance; when its box is not hidden as a whole, again at
  // its farthest, when every wall in front of any of its pixel centres has been added.
  // Occluders before objects at one distance; kObjectNode and after are the objects' events.
  enum Kind : std::uint32_t { kNode, kOccluder, kTerrain, kObjectNode, kObject, kObjectCentres };
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
  // from making this one stricter. The horizon's own verdicts take it too: an object whose top
  // lies a few µm under a wall's shadow plane is hidden exactly, and the horizon said so, where
  // that map showed it (Delft: one building in four cells).
  constexpr double kSightMargin = 1e-4;
  auto raised = [&](geometry::Box3 b) {
    b.zmax += kSightMargin;
    return b;
  };
  // The occluder that blocked this sample's last sight line, asked first by the next one.
  std::uint32_t blocker = std::numeric_limits<std::uint32_t>::max();
  auto point_hidden = [&](const SampleHorizon& h, Vec2 p, double top) {
    if (h.hides_point(p, top + kSightMargin)) return true;
    ++c.sight_lines;
    return sight_line_blocked(h.sample(), Vec3{p.x, p.y, top}, tree, scene_.occluders(),
                              kSightMargin, &blocker);
  };
  // The centres an object's outline touches, tile by tile for a large object: a tile whose
  // centres' box the horizon hides as a whole hides each of them, so a building hundreds of
  // metres long (a hall, a cut multipolygon kept over its box) is not asked about pixel by pixel
  // (a 2 km one, 2 million centres per sample, ran at 12 cells/s). Small objects keep the plain
  // scan, whose answers the tiles only reach sooner.
  constexpr long long kTile = 32;  // [pixels]
  // The centres in `t` of those object o's outline touches (r: all it touches).
  auto centres_hidden = [&](const SampleHorizon& h, std::uint32_t o,
                            const CullMapGrid::PixelRange& r, const CullMapGrid::PixelRange& t) {
    for (long long j = t.j0; j <= t.j1; ++j) {
      const PixelSpan row = outline_row(lattice, outlines[o], r, j);
      for (long long i = std::max(row.first, t.i0); i <= std::min(row.last, t.i1); ++i)
        if (!point_hidden(h, centre(i, j), objects[o].bbox.zmax)) return false;
    }
    return true;
  };
  auto points_hidden = [&](const SampleHorizon& h, std::uint32_t o) {
    const geometry::Box3& box = objects[o].bbox;
    const auto r = lattice.touched(box.xy);
    if ((r.i1 - r.i0 + 1) * (r.j1 - r.j0 + 1) <= 4 * kTile * kTile)
      return centres_hidden(h, o, r, r);
    for (long long tj = r.j0; tj <= r.j1; tj += kTile)
      for (long long ti = r.i0; ti <= r.i1; ti += kTile) {
        const CullMapGrid::PixelRange t{ti, tj, std::min(ti + kTile - 1, r.i1),
                                        std::min(tj + kTile - 1, r.j1)};
        if (h.hides_as_is(raised({{centre(t.i0, t.j0), centre(t.i1, t.j1)}, box.zmin, box.zmax})))
          continue;
        if (!centres_hidden(h, o, r, t)) return false;
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
    return bit(ask_, position_[o]) && seen_in_sweep_[o] != sweep_stamp_;
  };

  std::vector<Event>& heap = events_;
  {
    SampleHorizon& h = horizon_;
    h.reset(sample);
    // A sample asked about a few objects (one kept from a neighbouring cell, asked what this
    // cell's maps left open besides) watches only their directions: its sweep then skips the
    // occluders everywhere else, and its answers are the same (SampleHorizon::watch_none). A
    // quarter of the sweeps are such on the generated cities; each went on all round until it
    // passed the farthest of its objects.
    std::size_t asked = 0;
    for (const std::uint64_t w : ask_) asked += static_cast<std::size_t>(std::popcount(w));
    if (watch_ == SweepWatch::FewObjects && asked <= kWatchedAsk) {
      h.watch_none();
      bool narrow = true;
      for (std::size_t w = 0; w < ask_.size() && narrow; ++w)
        for_each_bit(ask_[w], w, [&](std::uint32_t k) {
          if (narrow) narrow = h.watch(raised(centres_box(object_at_[k])));
        });
      if (narrow) ++c.narrow_sweeps;
    }
    heap.clear();
    std::size_t object_events = 0;  // the sweep stops when no object is left to meet
    auto push = [&](double d, Kind kind, std::uint32_t id) {
      heap.push_back({d, kind, id});
      std::push_heap(heap.begin(), heap.end(), later);
      if (kind >= kObjectNode) ++object_events;
    };
    push(h.distance_to(node_box(0).xy), kObjectNode, 0);
    if (!horizon_tree_.nodes().empty())
      push(h.distance_to(horizon_tree_.nodes()[0].box.xy), kNode, 0);
    static const TerrainPyramid kNoTerrain;
    const TerrainPyramid& terrain = terrain_ ? *terrain_ : kNoTerrain;
    for (const std::uint32_t root : terrain.roots())
      push(h.distance_to(terrain.nodes()[root].box.xy), kTerrain, root);
    while (object_events > 0 && !heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const Event e = heap.back();
      heap.pop_back();
      if (e.kind >= kObjectNode) --object_events;
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
      } else if (e.kind == kTerrain) {
        // A square of the terrain, whole or split into its four as the sweep comes nearer than
        // kSplitRatio sides: the coarse one lies under its children, so it only hides less.
        const TerrainPyramid::Node& n = terrain.nodes()[e.id];
        if (h.hides(n.box)) continue;
        if (!terrain.split(n, e.distance)) {
          h.add(n.occluder);
          ++c.occluders_far_field;
          continue;
        }
        for (const std::int32_t child : n.child) {
          const auto k = static_cast<std::uint32_t>(child);
          push(h.distance_to(terrain.nodes()[k].box.xy), kTerrain, k);
        }
      } else if (e.kind == kObjectNode) {
        if (!any_asked(run_[e.id]) || h.hides_as_is(raised(node_box(e.id)))) continue;
        const BoxQuadtree::Node& n = nodes[e.id];
        for (std::uint32_t k = 0; k < n.count; ++k) {
          const std::uint32_t o = object_tree.items()[n.first + k];
          if (still_open(o)) push(h.distance_to(centres_box(o).xy), kObject, o);
        }
        for (std::int32_t child : n.child)
          if (child >= 0 && any_asked(run_[static_cast<std::size_t>(child)]))
            push(h.distance_to(node_box(static_cast<std::uint32_t>(child)).xy), kObjectNode,
                 static_cast<std::uint32_t>(child));
      } else if (e.kind == kObject) {
        const geometry::Box3 b = centres_box(e.id);
        if (!h.hides_as_is(raised(b))) push(farthest(h, b.xy), kObjectCentres, e.id);
      } else if (!points_hidden(h, e.id)) {
        seen_in_sweep_[e.id] = sweep_stamp_;
        seen.push_back(e.id);
      }
    }
  }
}

}  // namespace urbanpvs::preprocess
