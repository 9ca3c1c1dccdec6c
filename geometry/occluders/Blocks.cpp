// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/Blocks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "BoundarySimplification.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

struct Prism {
  std::uint32_t object;
  const Polygon* footprint;
  double top;
  Box2 box;
};

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d),
                   distance_to_segment(c, a, b), distance_to_segment(d, a, b)});
}

// True when the footprints overlap or come within `gap` of each other.
bool near(const Polygon& p, const Polygon& q, double gap) {
  if (inside(p, q.outer.front()) || inside(q, p.outer.front())) return true;
  bool found = false;
  for_each_edge(p, [&](Vec2 a, Vec2 b) {
    if (found) return;
    Box2 e;
    e.extend(a), e.extend(b);
    e = e.grown(gap);
    for_each_edge(q, [&](Vec2 c, Vec2 d) {
      if (found) return;
      Box2 f;
      f.extend(c), f.extend(d);
      if (e.overlaps(f) && segment_distance(a, b, c, d) <= gap) found = true;
    });
  });
  return found;
}

// Candidate pairs through a uniform grid of prism boxes: cities are large and sparse, so testing
// all pairs would be quadratic in the number of buildings.
void fuse_neighbours(const std::vector<Prism>& prisms, double gap, DisjointSets& sets) {
  Box2 all;
  for (const Prism& p : prisms) all.extend(p.box);
  const double cell = 50.0;
  auto key = [&](double x, double y) {
    const auto ix = static_cast<std::int64_t>(std::floor((x - all.min.x) / cell));
    const auto iy = static_cast<std::int64_t>(std::floor((y - all.min.y) / cell));
    return ix * 1000003 + iy;
  };
  std::map<std::int64_t, std::vector<std::size_t>> grid;
  for (std::size_t i = 0; i < prisms.size(); ++i) {
    const Box2 b = prisms[i].box.grown(gap);
    for (double x = std::floor((b.min.x - all.min.x) / cell); x * cell + all.min.x <= b.max.x; ++x)
      for (double y = std::floor((b.min.y - all.min.y) / cell); y * cell + all.min.y <= b.max.y;
           ++y)
        grid[key(all.min.x + (x + 0.5) * cell, all.min.y + (y + 0.5) * cell)].push_back(i);
  }
  for (const auto& [k, members] : grid)
    for (std::size_t a = 0; a < members.size(); ++a)
      for (std::size_t b = a + 1; b < members.size(); ++b) {
        const Prism& p = prisms[members[a]];
        const Prism& q = prisms[members[b]];
        if (sets.find(members[a]) == sets.find(members[b])) continue;
        if (p.box.grown(gap).overlaps(q.box) && near(*p.footprint, *q.footprint, gap))
          sets.join(members[a], members[b]);
      }
}

double quantised(double top, double step) {
  return step > 0 ? std::floor(top / step) * step : top;
}

// The level's outline simplified, where that leaves every ring simple; else as the union gave
// it. A ring that still crosses itself (the union's doubles, its micrometre pulls, on stepped
// roofs' many nearly coincident edges) is dropped: CGAL's straight skeleton checks no
// precondition and crashed on such a level of the 3D BAG tile, and an occluder may always be
// smaller.
std::vector<Polygon> valid_outline(std::vector<Polygon> exact, double tolerance) {
  std::vector<Polygon> simple = detail::simplify_boundaries(exact, tolerance);
  if (std::all_of(simple.begin(), simple.end(),
                  [](const Polygon& p) { return polygon_defect(p).empty(); }))
    return simple;
  std::erase_if(exact, [](const Polygon& p) { return !polygon_defect(p).empty(); });
  return exact;
}

Block build_block(std::vector<const Prism*> members, const BlockOptions& options) {
  Block block;
  std::sort(members.begin(), members.end(),
            [](const Prism* a, const Prism* b) { return a->top > b->top; });
  // Levels from the top down: each level is the union of every prism that reaches it. The union
  // grows in exact arithmetic (GrowingUnion) and is rounded to doubles only for the level's
  // outline: feeding a previous rounded union back in would feed CGAL rings pulled apart
  // where they touch, which can be slightly self-intersecting, a precondition CGAL's join does
  // not check (it crashed on a generated 1 km² city).
  GrowingUnion reaching;
  std::vector<BlockLevel> descending;
  for (std::size_t i = 0; i < members.size();) {
    const double level = quantised(members[i]->top, options.height_step);
    std::vector<Polygon> pieces;
    for (; i < members.size() && quantised(members[i]->top, options.height_step) == level; ++i) {
      block.objects.push_back(members[i]->object);
      block.bounds.extend(members[i]->box);
      for (Polygon& g : grow_polygon(*members[i]->footprint, 0.5 * options.gap_tolerance))
        pieces.push_back(std::move(g));
    }
    reaching.add(pieces);
    descending.push_back({level, valid_outline(reaching.polygons(), options.outline_tolerance),
                          0.5 * options.gap_tolerance + options.outline_tolerance});
  }
  std::sort(block.objects.begin(), block.objects.end());
  block.objects.erase(std::unique(block.objects.begin(), block.objects.end()), block.objects.end());
  block.levels.assign(descending.rbegin(), descending.rend());
  return block;
}

}  // namespace

std::vector<Block> build_blocks(const std::vector<CityObject>& objects,
                                const BlockOptions& options) {
  std::vector<Prism> prisms;
  for (const CityObject& o : objects)
    for (const OccluderPrism& p : o.occluders)
      prisms.push_back({o.index, &p.footprint, p.top_z, bounds(p.footprint)});
  DisjointSets sets(prisms.size());
  fuse_neighbours(prisms, options.gap_tolerance, sets);

  std::map<std::size_t, std::vector<const Prism*>> groups;  // root = smallest prism index
  for (std::size_t i = 0; i < prisms.size(); ++i) groups[sets.find(i)].push_back(&prisms[i]);
  std::vector<Block> blocks;
  blocks.reserve(groups.size());
  for (auto& [root, members] : groups) blocks.push_back(build_block(std::move(members), options));
  return blocks;
}

}  // namespace urbanpvs::geometry
