// SPDX-License-Identifier: GPL-3.0-or-later
// The sample horizon and the exact sight line against an independent ground truth: whatever it
// hides, every sight line from the sample to the box's top is cut by an occluder wall below the
// wall's top (2.5D prisms, segment against edge, no angles or sectors involved). Random scenes with
// convex and concave occluders and courtyards, in sweep order and out of it; and that it hides a
// fair share.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <utility>

#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"
#include "urbanpvs/preprocess/visibility/SightLine.hpp"
#include "urbanpvs/preprocess/visibility/SpatialIndex.hpp"

namespace urbanpvs::preprocess {
namespace {

using geometry::Box3;
using geometry::Occluder;
using geometry::Ring;

// True when the segment s→p passes through the wall over edge a–b of `o` below its top there.
bool wall_cuts(const Vec3& s, const Vec3& p, Vec2 a, Vec2 b, const Occluder& o) {
  const Vec2 s2{s.x, s.y}, d{p.x - s.x, p.y - s.y}, e = b - a;
  const double den = geometry::cross(d, e);
  if (den == 0) return false;
  const double t = geometry::cross(a - s2, e) / den;  // along s→p
  const double u = geometry::cross(a - s2, d) / den;  // along a→b
  if (!(t > 0 && t < 1 && u >= 0 && u <= 1)) return false;
  return s.z + t * (p.z - s.z) < o.top_at(a + u * e);
}

// True when p lies inside the solid of `o`: under its top, in its footprint and clear of every
// wall by a micrometre. A sight line from outside must enter the solid to reach it, whichever
// way it goes in. This decides the lines that pass exactly through a corner, where the rounding
// of wall_cuts can put the crossing just beyond the end of both walls that meet there.
bool inside_solid(const Vec3& p, const Occluder& o) {
  const Vec2 q{p.x, p.y};
  if (!(p.z < o.top_at(q)) || !geometry::inside(o.shape, q)) return false;
  bool clear = true;
  geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
    clear = clear && geometry::distance_to_segment(q, a, b) > 1e-6;
  });
  return clear;
}

bool blocked_by_walls(const Vec3& s, const Vec3& p, const std::vector<Occluder>& occluders) {
  for (const Occluder& o : occluders) {
    if (inside_solid(p, o)) return true;
    bool cut = false;
    geometry::for_each_edge(o.shape,
                            [&](Vec2 a, Vec2 b) { cut = cut || wall_cuts(s, p, a, b, o); });
    if (cut) return true;
  }
  return false;
}

// A star-shaped ring around `c` (concave when `jagged`), counter-clockwise.
Ring star(Vec2 c, double r, int n, bool jagged, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> f(0.5, 1.0);
  Ring ring;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    const double rr = r * (jagged ? (k % 2 ? 0.45 : 1.0) * f(rng) : 1.0);
    ring.push_back(c + Vec2{rr * std::cos(a), rr * std::sin(a)});
  }
  return ring;
}

Occluder make_occluder(geometry::Polygon shape, double top) {
  Occluder o;
  o.top_z = top;
  for (Vec2 p : shape.outer) o.bounds.extend(p);
  o.shape = std::move(shape);
  return o;
}

struct Item {
  double distance;
  int kind;  // 0 occluder, 1 box
  std::size_t index;
  bool operator<(const Item& o) const {
    return std::tie(distance, kind, index) < std::tie(o.distance, o.kind, o.index);
  }
};

// Sweeps occluders and boxes front to back from `sample`; returns which boxes it hides.
std::vector<bool> sweep(const Vec3& sample, const std::vector<Occluder>& occluders,
                        const std::vector<Box3>& boxes) {
  SampleHorizon h;
  h.reset(sample);
  std::vector<Item> items;
  for (std::size_t i = 0; i < occluders.size(); ++i)
    items.push_back({h.distance_to(occluders[i].bounds), 0, i});
  for (std::size_t i = 0; i < boxes.size(); ++i)
    items.push_back({h.distance_to(boxes[i].xy), 1, i});
  std::sort(items.begin(), items.end());
  std::vector<bool> hidden(boxes.size(), false);
  for (const Item& it : items) {
    if (it.kind == 0)
      h.add(occluders[it.index]);
    else
      hidden[it.index] = h.hides(boxes[it.index]);
  }
  return hidden;
}

// Every sight line from the sample to a grid of points over the box's top is blocked.
void expect_hidden_by_ground_truth(const Vec3& s, const Box3& box,
                                   const std::vector<Occluder>& occluders) {
  constexpr int kSteps = 12;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; j <= kSteps; ++j) {
      const Vec3 p{box.xy.min.x + (box.xy.max.x - box.xy.min.x) * i / kSteps,
                   box.xy.min.y + (box.xy.max.y - box.xy.min.y) * j / kSteps, box.zmax};
      ASSERT_TRUE(blocked_by_walls(s, p, occluders))
          << "sample (" << s.x << ", " << s.y << ", " << s.z << ") sees (" << p.x << ", " << p.y
          << ", " << p.z << ")";
    }
}

using Uniform = std::uniform_real_distribution<double>;

// Occluder k of a random scene: a star of 5 to 13 corners around a random centre, every third
// one concave; the centre and the shape.
std::pair<Vec2, geometry::Polygon> random_star(int k, Uniform& pos, Uniform& size,
                                               std::mt19937_64& rng) {
  const Vec2 c{pos(rng), pos(rng)};
  return {c, geometry::Polygon{star(c, size(rng), 5 + k % 9, k % 3 == 0, rng), {}}};
}

// A sample outside every occluder's bounds.
Vec3 free_sample(const std::vector<Occluder>& occluders, std::mt19937_64& rng, Uniform& pos,
                 Uniform& eye) {
  for (;;) {
    const Vec3 s{pos(rng), pos(rng), eye(rng)};
    if (std::none_of(occluders.begin(), occluders.end(), [&](const Occluder& o) {
          return s.x >= o.bounds.min.x && s.x <= o.bounds.max.x && s.y >= o.bounds.min.y &&
                 s.y <= o.bounds.max.y;
        }))
      return s;
  }
}

// 300 boxes over and around the scene, standing on the ground, with tops from `top`.
template <class Top>
std::vector<Box3> random_boxes(std::mt19937_64& rng, Uniform& pos, Uniform& size, Top&& top) {
  std::vector<Box3> boxes;
  for (int k = 0; k < 300; ++k) {
    Box3 b;
    const Vec2 c{pos(rng) * 1.5, pos(rng) * 1.5};
    b.xy.extend(c);
    b.xy.extend(c + Vec2{size(rng), size(rng)});
    b.zmin = 0;
    b.zmax = top();
    boxes.push_back(b);
  }
  return boxes;
}

// Sweeps `boxes` from `s` and checks every box it hides against the ground truth; counts the
// boxes tested and hidden.
void check_sweep(const Vec3& s, const std::vector<Occluder>& occluders,
                 const std::vector<Box3>& boxes, std::size_t& hidden, std::size_t& tested) {
  const std::vector<bool> h = sweep(s, occluders, boxes);
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    ++tested;
    if (!h[k]) continue;
    ++hidden;
    expect_hidden_by_ground_truth(s, boxes[k], occluders);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(SampleHorizon, HidesOnlyWhatEverySightLineShowsHidden) {
  std::mt19937_64 rng(21);
  Uniform pos(-200, 200), size(4, 30), top(3, 40), eye(0.5, 6), box_size(1, 15);
  std::size_t hidden = 0, tested = 0;
  for (int scene = 0; scene < 40; ++scene) {
    std::vector<Occluder> occluders;
    for (int k = 0; k < 60; ++k) {
      auto [c, shape] = random_star(k, pos, size, rng);
      if (k % 7 == 0) {  // a courtyard
        Ring hole = star(c, 0.3 * size(rng), 6, false, rng);
        std::reverse(hole.begin(), hole.end());
        shape.holes.push_back(hole);
      }
      occluders.push_back(make_occluder(std::move(shape), top(rng)));
    }
    const Vec3 s = free_sample(occluders, rng, pos, eye);
    check_sweep(s, occluders, random_boxes(rng, pos, box_size, [&] { return top(rng) * 0.8; }),
                hidden, tested);
    if (HasFatalFailure()) return;
  }
  // The test is not vacuous: in these dense scenes a good share is hidden.
  EXPECT_GT(hidden, tested / 10);
  std::printf("hidden %zu of %zu boxes\n", hidden, tested);
}

// A sweep that watches a few boxes' sectors (as the far field's sweeps asked about few objects
// do) skips every occluder whose box it finds hidden in them, so every occluder in another
// direction; it must still say of the watched boxes what a sweep that adds every occluder says,
// and count a box in no watched sector as hidden.
TEST(SampleHorizon, AWatchedSweepSaysOfItsBoxesWhatTheFullSweepSays) {
  std::mt19937_64 rng(29);
  Uniform pos(-200, 200), size(4, 30), top(3, 40), eye(0.5, 6), box_size(1, 15);
  std::size_t asked = 0, hidden = 0, skipped = 0, added = 0, outside = 0;
  for (int scene = 0; scene < 40; ++scene) {
    std::vector<Occluder> occluders;
    for (int k = 0; k < 60; ++k) {
      auto [c, shape] = random_star(k, pos, size, rng);
      occluders.push_back(make_occluder(std::move(shape), top(rng)));
    }
    const Vec3 s = free_sample(occluders, rng, pos, eye);
    const std::vector<Box3> boxes =
        random_boxes(rng, pos, box_size, [&] { return top(rng) * 0.8; });
    std::vector<std::size_t> watched;  // 1 to 4 boxes clear of the sample
    const std::size_t n = 1 + rng() % 4;
    for (std::size_t k = 0; k < boxes.size() && watched.size() < n; ++k)
      if (!boxes[k].xy.grown(1).overlaps({{s.x, s.y}, {s.x, s.y}})) watched.push_back(k);
    SampleHorizon full, few;
    full.reset(s);
    few.reset(s);
    few.watch_none();
    for (const std::size_t k : watched) ASSERT_TRUE(few.watch(boxes[k]));
    std::vector<Item> items;
    for (std::size_t i = 0; i < occluders.size(); ++i)
      items.push_back({full.distance_to(occluders[i].bounds), 0, i});
    for (const std::size_t k : watched) items.push_back({full.distance_to(boxes[k].xy), 1, k});
    std::sort(items.begin(), items.end());
    for (const Item& it : items) {
      if (it.kind == 1) {
        const bool h = full.hides_as_is(boxes[it.index]);
        ASSERT_EQ(few.hides_as_is(boxes[it.index]), h) << "scene " << scene << " box " << it.index;
        ++asked;
        hidden += h ? 1 : 0;
        continue;
      }
      const Occluder& o = occluders[it.index];
      full.add(o);
      if (few.hides({o.bounds, 0, o.top_z})) {
        ++skipped;
        continue;
      }
      few.add(o);
      ++added;
    }
    // A box straight behind the sample from the first watched one, far off: in no watched
    // sector when one box is watched.
    if (watched.size() == 1) {
      const Vec2 c = 0.5 * (boxes[watched[0]].xy.min + boxes[watched[0]].xy.max);
      const Vec2 away = Vec2{s.x, s.y} - 3.0 * (c - Vec2{s.x, s.y});
      const Box3 behind{{away - Vec2{0.5, 0.5}, away + Vec2{0.5, 0.5}}, 0, 1e7};
      EXPECT_TRUE(few.hides_as_is(behind));
      EXPECT_FALSE(full.hides_as_is(behind));  // nothing hides a top 10,000 km high
      ++outside;
    }
  }
  // Not vacuous: boxes both hidden and seen, and most occluders skipped.
  EXPECT_GT(hidden, 0u);
  EXPECT_LT(hidden, asked);
  EXPECT_GT(skipped, added);
  EXPECT_GT(outside, 0u);
}

// Looking down from a hillside: every top lies below the eye, some of them sloped, some of them
// thin walls seen at a slant, where the crossings within a sector lie far apart. A ray that
// passes a facing wall below its top enters the occluder (thesis 4.2.1) whether the wall rises
// above the eye or not; the horizon counts such walls from their nearest crossing in a sector.
TEST(SampleHorizon, WallsBelowTheEyeHideOnlyWhatEverySightLineShowsHidden) {
  std::mt19937_64 rng(23);
  Uniform pos(-200, 200), size(4, 30), top(3, 25), eye(50, 70), box_size(1, 15), slope(-0.3, 0.3),
      box_top(0.5, 20);
  std::size_t hidden = 0, tested = 0;
  for (int scene = 0; scene < 40; ++scene) {
    std::vector<Occluder> occluders;
    for (int k = 0; k < 60; ++k) {
      auto [c, shape] = random_star(k, pos, size, rng);
      if (k % 4 == 0) {  // a thin wall, 0.5 m by up to 80 m, in any direction
        const double a = Uniform(0, std::numbers::pi)(rng);
        const Vec2 u{std::cos(a), std::sin(a)}, v{-u.y, u.x};
        const double half = 2 * size(rng);
        shape.outer = {c - half * u - 0.25 * v, c + half * u - 0.25 * v, c + half * u + 0.25 * v,
                       c - half * u + 0.25 * v};
      }
      Occluder o = make_occluder(std::move(shape), top(rng));
      if (scene % 2 == 1) {  // a sloped top, lowest at least 1 m above the ground
        o.slope = {slope(rng), slope(rng)};
        o.origin = c;
        if (o.top_low() < 1) o.top_z += 1 - o.top_low();
      }
      occluders.push_back(std::move(o));
    }
    const Vec3 s = free_sample(occluders, rng, pos, eye);
    for (const Occluder& o : occluders) ASSERT_LT(o.top_high(), s.z);
    check_sweep(s, occluders, random_boxes(rng, pos, box_size, [&] { return box_top(rng); }),
                hidden, tested);
    if (HasFatalFailure()) return;
  }
  // Walls below the eye hide a share: a horizon that skipped them would hide nothing here.
  EXPECT_GT(hidden, tested / 20);
  std::printf("hidden %zu of %zu boxes\n", hidden, tested);
}

TEST(SampleHorizon, AConvexBlockHidesWhatIsLowerBehindIt) {
  // A 20 m block 10 m high from x = 10 to 30; the eye at 2 m at the origin. Its front wall
  // hides, 40 m away, up to 2 + 40·(10 - 2)/10 = 34 m: a box 30 m high behind the block is
  // hidden, one 40 m high is not, nor one beside the block (the block spans ±45°).
  std::vector<Occluder> occ{make_occluder({{{10, -10}, {30, -10}, {30, 10}, {10, 10}}, {}}, 10)};
  const Vec3 s{0, 0, 2};
  auto box = [](double x0, double y0, double x1, double y1, double z) {
    Box3 b;
    b.xy = {{x0, y0}, {x1, y1}};
    b.zmin = 0;
    b.zmax = z;
    return b;
  };
  const std::vector<Box3> boxes{box(40, -2, 45, 2, 30), box(40, -2, 45, 2, 40),
                                box(40, 50, 45, 55, 5)};
  const std::vector<bool> h = sweep(s, occ, boxes);
  EXPECT_TRUE(h[0]);
  EXPECT_FALSE(h[1]);
  EXPECT_FALSE(h[2]);
}

TEST(SampleHorizon, ACourtyardHidesEverythingLowOutsideIt) {
  // A square block 50 m wide, 15 m high, with a courtyard 20 m wide; the eye in the courtyard.
  Ring hole{{-10, -10}, {-10, 10}, {10, 10}, {10, -10}};  // clockwise
  std::vector<Occluder> occ{
      make_occluder({{{-25, -25}, {25, -25}, {25, 25}, {-25, 25}}, {hole}}, 15)};
  const Vec3 s{3, -2, 2};
  std::vector<Box3> boxes;
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * std::numbers::pi * k / 16;
    Box3 b;
    b.xy.extend(Vec2{60 * std::cos(a), 60 * std::sin(a)});
    b.xy.extend(Vec2{60 * std::cos(a) + 4, 60 * std::sin(a) + 4});
    b.zmin = 0;
    b.zmax = 8;
    boxes.push_back(b);
  }
  const std::vector<bool> h = sweep(s, occ, boxes);
  for (std::size_t k = 0; k < boxes.size(); ++k) EXPECT_TRUE(h[k]) << "box " << k;
}

TEST(SampleHorizon, ACourtyardRunAroundTheSampleCountsBothWallsAtItsSeam) {
  // An L-shaped courtyard, two arms 10 m wide and 100 m long, in a block 15 m high; the eye 2 m
  // up in the square where the arms meet sees every wall of it: one run of facing walls around
  // the eye, starting and ending at vertex 0, the inner corner (10, 10). The eye sits 9 m from
  // that corner and just beside the line of one of its walls, the corner's direction in the
  // middle of a sector: in that one sector the rays on one side of the corner leave through the
  // other wall 9 m out, those on the other side run along the arm, grazing its wall, up to
  // ~99 m. The sector may only count the courtyard's walls from the farther crossing; counting
  // one end of the run alone, it hides the arm beyond 9 m. Both ways round (mirrored in y = x,
  // which maps the courtyard onto itself): the grazing wall is the run's last, then its first.
  const Ring hole{{10, 10}, {100, 10}, {100, 0}, {0, 0}, {0, 100}, {10, 100}};  // clockwise
  const std::vector<Occluder> occ{
      make_occluder({{{-20, -20}, {120, -20}, {120, 120}, {-20, 120}}, {hole}}, 15)};
  const double sector = 2 * std::numbers::pi / SampleHorizon::kBins;
  const long long seam = SampleHorizon::kBins / 4 - 1;  // the sector just below 90°
  const double corner = (static_cast<double>(seam) + 0.5) * sector;
  for (const bool mirrored : {false, true}) {
    auto place = [&](Vec2 p) { return mirrored ? Vec2{p.y, p.x} : p; };
    const Vec2 eye{10 - 9 * std::cos(corner), 10 - 9 * std::sin(corner)};
    const Vec3 s{place(eye).x, place(eye).y, 2};
    SampleHorizon h;
    h.reset(s);
    h.add(occ[0]);
    std::size_t hidden = 0, loose = 0;
    // Points along rays across the seam's sector, from the courtyard out past the block.
    for (int f = 1; f < 16; ++f) {
      const double a = (static_cast<double>(seam) + f / 16.0) * sector;
      for (double d = 1; d <= 130; d += 0.5)
        for (const double z : {0.0, 1.0, 8.0, 14.0}) {
          const Vec2 p = place(eye + d * Vec2{std::cos(a), std::sin(a)});
          const bool truth = blocked_by_walls(s, Vec3{p.x, p.y, z}, occ);
          if (h.hides_point(p, z)) {
            ++hidden;
            ASSERT_TRUE(truth) << (mirrored ? "mirrored: " : "") << "sample (" << s.x << ", " << s.y
                               << ") sees (" << p.x << ", " << p.y << ", " << z
                               << ") but the horizon hides it";
          } else if (truth) {
            ++loose;
          }
        }
    }
    // A box along the arm, 20 to 90 m out, in plain view down the courtyard.
    Box3 b;
    b.xy.extend(place(Vec2{9.99, 20}));
    b.xy.extend(place(Vec2{9.995, 90}));
    b.zmax = 1;
    if (h.hides(b)) expect_hidden_by_ground_truth(s, b, occ);
    if (HasFatalFailure()) return;
    // Not vacuous: beyond the block the seam's sector still hides what is low.
    EXPECT_GT(hidden, 100u) << (mirrored ? "mirrored" : "");
    std::printf("%s: hidden %zu points; %zu more hidden by the walls alone\n",
                mirrored ? "mirrored" : "plain", hidden, loose);
  }
}

TEST(SampleHorizon, PointsAndOutOfOrderQueriesStayConservative) {
  // Every wall added first, then boxes in random order and single points: whatever is hidden,
  // every sight line shows hidden.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> pos(-150, 150), size(4, 25), top(3, 40), eye(0.5, 6);
  std::size_t hidden = 0;
  for (int scene = 0; scene < 30; ++scene) {
    std::vector<Occluder> occluders;
    for (int k = 0; k < 50; ++k)
      occluders.push_back(make_occluder(
          {star(Vec2{pos(rng), pos(rng)}, size(rng), 4 + k % 7, k % 2 == 0, rng), {}}, top(rng)));
    Vec3 s{pos(rng), pos(rng), eye(rng)};
    SampleHorizon h;
    h.reset(s);
    for (const Occluder& o : occluders) h.add(o);
    for (int k = 0; k < 400; ++k) {
      const Vec2 p{pos(rng) * 1.3, pos(rng) * 1.3};
      const double z = top(rng) * 0.8;
      if (k % 2 == 0) {
        Box3 b;
        b.xy.extend(p);
        b.xy.extend(p + Vec2{size(rng) * 0.3, size(rng) * 0.3});
        b.zmax = z;
        if (!h.hides(b)) continue;
        ++hidden;
        expect_hidden_by_ground_truth(s, b, occluders);
      } else {
        if (!h.hides_point(p, z)) continue;
        ++hidden;
        ASSERT_TRUE(blocked_by_walls(s, Vec3{p.x, p.y, z}, occluders));
      }
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(hidden, 1000u);
}

TEST(SightLine, AgreesWithEveryDrawnWallTestedInTurn) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> pos(-150, 150), size(4, 25), top(3, 40), eye(0.5, 6);
  std::vector<Occluder> occluders;
  std::vector<Box3> boxes;
  for (int k = 0; k < 80; ++k) {
    occluders.push_back(make_occluder(
        {star(Vec2{pos(rng), pos(rng)}, size(rng), 4 + k % 7, k % 2 == 0, rng), {}}, top(rng)));
    Box3 b;
    b.xy = occluders.back().bounds;
    b.zmax = occluders.back().top_z;
    boxes.push_back(b);
  }
  const BoxQuadtree tree(boxes, 4);
  int blocked = 0;
  std::uint32_t last_blocker = 1000;  // none yet
  for (int k = 0; k < 4000; ++k) {
    const Vec3 s{pos(rng), pos(rng), eye(rng)}, p{pos(rng), pos(rng), top(rng)};
    // The walls a map draws: those facing s, and every wall of an occluder s is above.
    bool expected = false;
    for (const Occluder& o : occluders)
      geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
        const bool drawn = s.z > o.top_z || geometry::cross(b - a, Vec2{s.x, s.y} - a) < 0;
        expected = expected || (drawn && wall_cuts(s, p, a, b, o));
      });
    ASSERT_EQ(sight_line_blocked(s, p, tree, occluders, 0), expected) << k;
    // Asking an occluder first (the last blocker, or one at random) gives the same answer, and
    // the blocker named blocks the line alone.
    for (std::uint32_t first : {last_blocker, static_cast<std::uint32_t>(rng() % 100)}) {
      std::uint32_t named = first;
      ASSERT_EQ(sight_line_blocked(s, p, tree, occluders, 0, &named), expected) << k;
      if (!expected) continue;
      ASSERT_LT(named, occluders.size()) << k;
      const std::vector<Occluder> alone{occluders[named]};
      const BoxQuadtree one(std::vector<Box3>{boxes[named]}, 4);
      ASSERT_TRUE(sight_line_blocked(s, p, one, alone, 0)) << k;
      last_blocker = named;
    }
    blocked += expected ? 1 : 0;
  }
  EXPECT_GT(blocked, 1000);
  EXPECT_LT(blocked, 3900);
}

}  // namespace
}  // namespace urbanpvs::preprocess
