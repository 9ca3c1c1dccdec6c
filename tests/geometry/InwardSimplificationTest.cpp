// SPDX-License-Identifier: GPL-3.0-or-later
// Property tests of simplified_inward, the far field's outlines: the result must lie inside the
// input (a larger occluder could hide what the real one shows), keep every ring, and cut away
// no input vertex farther than the tolerance from the chord that replaced it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "PolygonTestShapes.hpp"
#include "urbanpvs/geometry/occluders/InwardSimplification.hpp"

namespace urbanpvs::geometry {
namespace {

bool properly_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool simple(const Polygon& p) {
  bool ok = true;
  for_each_edge(p, [&](Vec2 a, Vec2 b) {
    for_each_edge(p, [&](Vec2 c, Vec2 d) { ok = ok && !properly_cross(a, b, c, d); });
  });
  return ok;
}

// A ring with a vertex added on every edge, a little off it to either side: the many short,
// slightly bent walls of real outlines (the star rings alone have few, long ones).
Ring bent(const Ring& r, std::mt19937_64& rng, double offset) {
  std::uniform_real_distribution<double> u(-1, 1);
  Ring out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()];
    const Vec2 d = b - a;
    const double len = std::hypot(d.x, d.y);
    out.push_back(a);
    if (len > 4 * offset) out.push_back(0.5 * (a + b) + (offset * u(rng) / len) * Vec2{-d.y, d.x});
  }
  return out;
}

// Checks the contract for one polygon and tolerance; `out` is the result.
void check(const Polygon& in, double tolerance, std::mt19937_64& rng, const std::string& what,
           Polygon& out) {
  out = simplified_inward(in, tolerance);
  std::vector<const Ring*> rin{&in.outer}, rout{&out.outer};
  for (const Ring& h : in.holes) rin.push_back(&h);
  for (const Ring& h : out.holes) rout.push_back(&h);
  ASSERT_EQ(rout.size(), rin.size()) << what;
  for (std::size_t r = 0; r < rin.size(); ++r) {
    const Ring& a = *rin[r];
    const Ring& b = *rout[r];
    EXPECT_GE(b.size(), std::min<std::size_t>(3, a.size())) << what;
    // The result's vertices are the input's, in order; each input vertex cut away lies within
    // the tolerance of the line of the result's edge that spans it.
    std::map<std::pair<double, double>, std::size_t> index;
    for (std::size_t k = 0; k < a.size(); ++k) index[{a[k].x, a[k].y}] = k;
    std::vector<std::size_t> kept;
    for (Vec2 p : b) {
      const auto it = index.find({p.x, p.y});
      ASSERT_NE(it, index.end()) << what << ": a vertex the input does not have";
      kept.push_back(it->second);
    }
    for (std::size_t e = 0; e < kept.size(); ++e) {
      const std::size_t i = kept[e], j = kept[(e + 1) % kept.size()];
      const Vec2 p = a[i], q = a[j];
      const double len = std::hypot(q.x - p.x, q.y - p.y);
      std::size_t steps = 0;
      for (std::size_t k = (i + 1) % a.size(); k != j; k = (k + 1) % a.size(), ++steps) {
        ASSERT_LT(steps, a.size()) << what << ": vertices out of order";
        EXPECT_LE(std::abs(cross(q - p, a[k] - p)) / len, tolerance + 1e-9)
            << what << ": input vertex " << k << " of ring " << r << " cut away too far";
      }
    }
  }
  // Inside: no edge of the result properly crosses one of the input, and every random point
  // inside the result is inside the input.
  for_each_edge(out, [&](Vec2 a, Vec2 b) {
    for_each_edge(in, [&](Vec2 c, Vec2 d) {
      EXPECT_FALSE(properly_cross(a, b, c, d)) << what << ": an edge leaves the input";
    });
  });
  const Box2 box = bounds(in);
  std::uniform_real_distribution<double> ux(box.min.x, box.max.x), uy(box.min.y, box.max.y);
  for (int k = 0; k < 400; ++k) {
    const Vec2 p{ux(rng), uy(rng)};
    if (inside(out, p)) {
      EXPECT_TRUE(inside(in, p)) << what << ": point " << p.x << " " << p.y;
    }
  }
  EXPECT_LE(area(out), area(in) * (1 + 1e-12)) << what;
}

TEST(InwardSimplification, RandomPolygonsStayInsideWithinTolerance) {
  std::mt19937_64 rng(17);
  int checked = 0;
  for (int i = 0; i < 300; ++i) {
    Polygon p = test::random_star_polygon(rng);
    // Half of them with bent walls, outer ring and holes alike.
    if (i % 2 == 1) {
      p.outer = bent(p.outer, rng, 0.3);
      for (Ring& h : p.holes) h = bent(h, rng, 0.1);
      if (!simple(p)) continue;  // a bend may cross a wall near a sharp corner
    }
    ++checked;
    for (double tolerance : {0.0, 0.1, 0.5, 2.0}) {
      Polygon out;
      check(p, tolerance, rng,
            "polygon " + std::to_string(i) + ", tolerance " + std::to_string(tolerance), out);
    }
  }
  EXPECT_GT(checked, 250);
}

TEST(InwardSimplification, OutwardBumpsWithinToleranceGo) {
  // A 40 m square whose walls each bulge 0.3 m outwards at their middle, with a hole whose
  // walls bulge into the solid: within 0.5 m every bulge is cut, beyond 0.2 m none.
  const Polygon in{
      {{0, 0}, {20, -0.3}, {40, 0}, {40.3, 20}, {40, 40}, {20, 40.3}, {0, 40}, {-0.3, 20}},
      {{{10, 10}, {9.7, 20}, {10, 30}, {20, 30.3}, {30, 30}, {30.3, 20}, {30, 10}, {20, 9.7}}}};
  std::mt19937_64 rng(11);
  Polygon out;
  check(in, 0.5, rng, "bumps", out);
  EXPECT_EQ(out.outer, (Ring{{0, 0}, {40, 0}, {40, 40}, {0, 40}}));
  ASSERT_EQ(out.holes.size(), 1u);
  EXPECT_EQ(out.holes[0], in.holes[0]);  // a hole's bulges into the solid are its concave corners
  check(in, 0.2, rng, "bumps", out);
  EXPECT_EQ(out.outer, in.outer);
}

TEST(InwardSimplification, RoundOutlineKeepsFewCorners) {
  // A round tower of radius 20 m drawn with 400 vertices: a chord of length c sags c²/8R below
  // the circle, so within 0.5 m about 14 chords go round it.
  Ring ring;
  for (int k = 0; k < 400; ++k) {
    const double a = 2 * std::numbers::pi * k / 400;
    ring.push_back({20 * std::cos(a), 20 * std::sin(a)});
  }
  std::mt19937_64 rng(3);
  Polygon out;
  check(Polygon{ring, {}}, 0.5, rng, "round tower", out);
  EXPECT_LE(out.outer.size(), 40u);
  EXPECT_GE(out.outer.size(), 14u);
}

TEST(InwardSimplification, StraightVerticesGoAtToleranceZero) {
  // A rectangle with a vertex in the middle of each side, and a square hole turned clockwise.
  const Polygon in{{{0, 0}, {5, 0}, {10, 0}, {10, 3}, {10, 6}, {5, 6}, {0, 6}, {0, 3}},
                   {{{2, 2}, {2, 4}, {4, 4}, {4, 2}}}};
  std::mt19937_64 rng(5);
  Polygon out;
  check(in, 0, rng, "rectangle", out);
  EXPECT_EQ(out.outer, (Ring{{0, 0}, {10, 0}, {10, 6}, {0, 6}}));
  ASSERT_EQ(out.holes.size(), 1u);
  EXPECT_EQ(out.holes[0], in.holes[0]);  // a corner of a hole is concave for the solid
}

TEST(InwardSimplification, ConcaveCornerIsNeverCut) {
  // An L whose inner corner (4, 4) is 2.8 m from the chord that would replace it.
  const Polygon in{{{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}}, {}};
  std::mt19937_64 rng(7);
  Polygon out;
  check(in, 3, rng, "L", out);
  EXPECT_NE(std::find(out.outer.begin(), out.outer.end(), Vec2{4, 4}), out.outer.end());
}

TEST(InwardSimplification, LongStraightWallsOfManyVertices) {
  // A 5,000 m by 10 m strip drawn with 2,000 vertices on each long wall: a chord replaces at
  // most 64 of them (which keeps each cut's work bounded), so the walls keep about one in 65.
  Ring ring;
  for (int k = 0; k < 2000; ++k) ring.push_back({2.5 * k, 0});
  for (int k = 0; k < 2000; ++k) ring.push_back({5000 - 2.5 * k, 10});
  std::mt19937_64 rng(19);
  Polygon out;
  check(Polygon{ring, {}}, 1, rng, "strip", out);
  EXPECT_LE(out.outer.size(), 2 * (2000 / 64 + 2));
  EXPECT_GE(out.outer.size(), 2 * (2000 / 65));
}

TEST(InwardSimplification, NoCutPastAnotherRing) {
  // The top wall bulges 0.3 m at (20, 40.3), and a hole reaches up to (20, 40.1) under it:
  // cutting the bulge would leave that corner of the hole outside the polygon.
  const Polygon in{{{0, 0}, {40, 0}, {40, 40}, {20, 40.3}, {0, 40}},
                   {{{19, 39}, {20, 40.1}, {21, 39}}}};
  std::mt19937_64 rng(13);
  Polygon out;
  check(in, 0.5, rng, "hole under a bulge", out);
  EXPECT_EQ(out.outer, in.outer);
}

}  // namespace
}  // namespace urbanpvs::geometry
