// SPDX-License-Identifier: GPL-3.0-or-later
// Occluders with sloped tops (thesis 4.2.1: the shadow of a sloped edge is bounded by the plane
// through the sample and the edge) against a ground truth that knows nothing of shadows,
// wedges, walls or sectors: a segment is blocked when some part of it lies inside a prism,
// below its top plane, found by cutting the segment at the prism's edges and comparing two
// linear functions on each piece inside. The CPU cull map, the exact sight line and the sample
// horizon are checked against it on random tilted prisms, convex and concave.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"
#include "urbanpvs/preprocess/visibility/OccluderShadow.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"
#include "urbanpvs/preprocess/visibility/SightLine.hpp"
#include "urbanpvs/preprocess/visibility/SpatialIndex.hpp"

namespace urbanpvs::preprocess {
namespace {

using geometry::Occluder;

// How far below the prism's top plane the segment s→p dips at its deepest, over the parts of
// it inside the prism's footprint (negative: it stays above; -infinity: it misses the
// footprint). On each piece between two edge crossings both the segment and the plane are
// linear, so the deepest point is an end of a piece.
double deepest(const Vec3& s, const Vec3& p, const Occluder& o) {
  const Vec2 s2{s.x, s.y}, d{p.x - s.x, p.y - s.y};
  std::vector<double> cuts{0.0, 1.0};
  geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
    const Vec2 e = b - a;
    const double den = geometry::cross(d, e);
    if (den == 0) return;
    const double t = geometry::cross(a - s2, e) / den;
    const double u = geometry::cross(a - s2, d) / den;
    if (t > 0 && t < 1 && u >= 0 && u <= 1) cuts.push_back(t);
  });
  std::sort(cuts.begin(), cuts.end());
  double worst = -std::numeric_limits<double>::infinity();
  auto at = [&](double t) { return s2 + t * d; };
  auto below = [&](double t) { return o.top_at(at(t)) - (s.z + t * (p.z - s.z)); };
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double t0 = cuts[k], t1 = cuts[k + 1];
    if (!(t1 > t0) || !geometry::inside(o.shape, at(0.5 * (t0 + t1)))) continue;
    worst = std::max({worst, below(t0), below(t1)});
  }
  return worst;
}

double deepest(const Vec3& s, const Vec3& p, const std::vector<Occluder>& occluders) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const Occluder& o : occluders) worst = std::max(worst, deepest(s, p, o));
  return worst;
}

// A random prism with a tilted top: a star-shaped ring around `c` (concave when `jagged`),
// counter-clockwise, top plane through (c, z) with a slope of up to 45°.
Occluder tilted_prism(Vec2 c, double r, bool jagged, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> f(0.5, 1.0), g(-1.0, 1.0), z(6.0, 25.0);
  const int n = jagged ? 8 : 5;
  Occluder o;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * (k + 0.3 * g(rng)) / n;
    const double rr = r * (jagged ? (k % 2 ? 0.45 : 1.0) * f(rng) : f(rng));
    o.shape.outer.push_back(c + Vec2{rr * std::cos(a), rr * std::sin(a)});
  }
  for (Vec2 p : o.shape.outer) o.bounds.extend(p);
  o.origin = c;
  o.top_z = z(rng);
  o.slope = {0.7 * g(rng), 0.7 * g(rng)};
  return o;
}

std::vector<Occluder> random_scene(std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> pos(-60, 60), size(4, 14);
  std::vector<Occluder> out;
  for (int i = 0; i < count; ++i) {
    const Vec2 c{pos(rng), pos(rng)};
    if (std::hypot(c.x, c.y) < 18) continue;  // the samples stand near the origin
    out.push_back(tilted_prism(c, size(rng), i % 2 == 1, rng));
  }
  return out;
}

Vec3 random_sample(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> xy(-4, 4), z(0, 30);
  return {xy(rng), xy(rng), z(rng)};
}

TEST(SlopedShadow, PlanePassesThroughTheSampleAndBothEndsOfTheEdge) {
  const Vec3 v{0, -10, 2};
  const Vec2 a{-5, 0}, b{5, 0};
  const auto s = occluder_shadow(v, a, 8.0, b, 14.0, 11.0, {{-100, -100}, {100, 100}});
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->height(a), 8.0, 1e-9);
  EXPECT_NEAR(s->height(b), 14.0, 1e-9);
  EXPECT_NEAR(s->height({v.x, v.y}), v.z, 1e-9);
  // Behind the edge's middle, twice as far from the sample: twice the rise over the sample
  // that the edge has there (11 − 2 = 9).
  EXPECT_NEAR(s->height({0, 10}), 2 + 2 * 9.0, 1e-9);
  // The flat form is the sloped one with equal ends.
  const auto flat = occluder_shadow(v, a, b, 11.0, {{-100, -100}, {100, 100}});
  const auto same = occluder_shadow(v, a, 11.0, b, 11.0, 11.0, {{-100, -100}, {100, 100}});
  ASSERT_TRUE(flat && same);
  EXPECT_EQ(flat->a, same->a);
  EXPECT_EQ(flat->b, same->b);
  EXPECT_EQ(flat->c, same->c);
}

TEST(SlopedShadow, FromAboveTheTopPlaneEveryWallCastsOne) {
  Occluder o;
  o.shape.outer = {{-5, 5}, {5, 5}, {5, 15}, {-5, 15}};
  for (Vec2 p : o.shape.outer) o.bounds.extend(p);
  o.origin = {0, 10};
  o.top_z = 10;
  o.slope = {0, -1};  // the top plane is 20 m high at y = 0, under the sample
  int below = 0, above = 0;
  for_each_shadow({0, 0, 19.5}, o, {{-100, -100}, {100, 100}},
                  [&](const OccluderShadow&) { ++below; });
  for_each_shadow({0, 0, 20.5}, o, {{-100, -100}, {100, 100}},
                  [&](const OccluderShadow&) { ++above; });
  EXPECT_EQ(below, 1);  // only the wall facing the sample
  EXPECT_EQ(above, 4);  // a line may come down through the top and leave through any wall
}

// Each pixel centre of one sample's CPU map against the deepest-point ground truth: the map
// never claims a centre hidden higher than the prisms hide it (conservative), and it claims
// the prisms' full height, to float precision, at almost every centre.
TEST(SlopedOccluder, CpuMapMatchesTheGroundTruthAtPixelCentres) {
  std::mt19937_64 rng(17);
  const CullMapGrid grid = CullMapGrid::covering({{-90, -90}, {90, 90}}, 1.3);
  std::size_t checked = 0, tight = 0, hidden = 0;
  for (int scene = 0; scene < 12; ++scene) {
    const std::vector<Occluder> occluders = random_scene(rng, 10);
    const Vec3 sample = random_sample(rng);
    std::vector<const Occluder*> pointers;
    for (const Occluder& o : occluders) pointers.push_back(&o);
    CullMap map(grid);
    render_sample(sample, pointers, map);
    for (int j = 0; j < grid.height; j += 3)
      for (int i = 0; i < grid.width; i += 3) {
        const Vec2 c = grid.center(i, j);
        const double m = map.at(i, j);
        if (std::hypot(c.x - sample.x, c.y - sample.y) < 1) continue;
        ++checked;
        // The highest hidden point over c: where the segment just grazes a top. Bisection on
        // its height (lower ends dip deeper: monotone).
        double lo = -200, hi = 400;
        if (deepest(sample, {c.x, c.y, lo}, occluders) <= 0) lo = hi = -1e30;
        for (int k = 0; k < 60 && hi > lo; ++k) {
          const double mid = 0.5 * (lo + hi);
          (deepest(sample, {c.x, c.y, mid}, occluders) > 0 ? lo : hi) = mid;
        }
        const double truth = lo;
        if (truth > -1e29) ++hidden;
        ASSERT_LE(m, truth + 1e-6) << "scene " << scene << " pixel " << i << "," << j;
        if (truth <= -1e29 ? m == CullMap::kNothingHidden : m >= truth - 1e-3) ++tight;
      }
  }
  EXPECT_GT(hidden, checked / 10);
  EXPECT_GT(tight, checked * 98 / 100) << tight << " of " << checked;
}

TEST(SlopedOccluder, SightLineAgreesWithTheGroundTruth) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> pos(-90, 90), z(-5, 40);
  std::size_t blocked = 0, total = 0;
  for (int scene = 0; scene < 20; ++scene) {
    const std::vector<Occluder> occluders = random_scene(rng, 10);
    std::vector<geometry::Box3> boxes;
    for (const Occluder& o : occluders) {
      geometry::Box3 b;
      b.xy = o.bounds;
      b.zmin = -std::numeric_limits<double>::infinity();
      b.zmax = o.top_high();
      boxes.push_back(b);
    }
    const BoxQuadtree tree(boxes);
    for (int k = 0; k < 400; ++k) {
      const Vec3 from = random_sample(rng);
      const Vec3 to{pos(rng), pos(rng), z(rng)};
      const double dip = deepest(from, to, occluders);
      if (std::abs(dip) < 1e-6) continue;  // grazing: either answer is right
      bool ends_inside = false;
      for (const Occluder& o : occluders)
        ends_inside = ends_inside || geometry::inside(o.shape, {to.x, to.y}) ||
                      geometry::inside(o.shape, {from.x, from.y});
      if (ends_inside) continue;
      ++total;
      const bool truth = dip > 0;
      blocked += truth ? 1 : 0;
      ASSERT_EQ(sight_line_blocked(from, to, tree, occluders, 0), truth)
          << "scene " << scene << " segment " << k;
    }
  }
  EXPECT_GT(blocked, total / 10);
  EXPECT_LT(blocked, total * 9 / 10);
}

// Whatever the horizon hides (points and whole boxes, swept front to back), every sight line
// from the sample to it dips into a prism; and it hides a fair share.
TEST(SlopedOccluder, HorizonHidesOnlyWhatTheGroundTruthHides) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> pos(-90, 90), z(0, 40), u(0, 1);
  std::size_t hidden = 0, truly = 0;
  for (int scene = 0; scene < 20; ++scene) {
    std::vector<Occluder> occluders = random_scene(rng, 12);
    const Vec3 sample = random_sample(rng);
    SampleHorizon h;
    h.reset(sample);
    std::sort(occluders.begin(), occluders.end(), [&](const Occluder& a, const Occluder& b) {
      return h.distance_to(a.bounds) < h.distance_to(b.bounds);
    });
    for (const Occluder& o : occluders) h.add(o);
    for (int k = 0; k < 1500; ++k) {
      const Vec2 p{pos(rng), pos(rng)};
      const double top = z(rng);
      const bool in_footprint =
          std::any_of(occluders.begin(), occluders.end(),
                      [&](const Occluder& o) { return geometry::inside(o.shape, p); });
      if (in_footprint || std::hypot(p.x - sample.x, p.y - sample.y) < 1) continue;
      const bool truth = deepest(sample, {p.x, p.y, top}, occluders) > 0;
      truly += truth ? 1 : 0;
      if (!h.hides_point(p, top)) continue;
      ++hidden;
      ASSERT_TRUE(truth) << "scene " << scene << " point " << p.x << "," << p.y << "," << top;
    }
    // Boxes: hidden as a whole means every point of their top (sampled) is hidden.
    for (int k = 0; k < 200; ++k) {
      geometry::Box3 b;
      const Vec2 c{pos(rng), pos(rng)};
      b.xy = {c, c + Vec2{1 + 4 * u(rng), 1 + 4 * u(rng)}};
      b.zmin = 0;
      b.zmax = z(rng);
      if (!h.hides_as_is(b)) continue;
      for (int m = 0; m < 16; ++m) {
        const Vec2 q{b.xy.min.x + u(rng) * (b.xy.max.x - b.xy.min.x),
                     b.xy.min.y + u(rng) * (b.xy.max.y - b.xy.min.y)};
        ASSERT_GT(deepest(sample, {q.x, q.y, b.zmax}, occluders), -1e-9)
            << "scene " << scene << " box " << k;
      }
    }
  }
  EXPECT_GT(hidden, truly / 4) << hidden << " of " << truly;
}

}  // namespace
}  // namespace urbanpvs::preprocess
