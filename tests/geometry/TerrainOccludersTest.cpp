// SPDX-License-Identifier: GPL-3.0-or-later
// The terrain's occluders (TerrainOccluders.hpp, thesis 7.3.2 and 7.4): exact levels on a
// ramp, one level where the ground is flat, and the property that makes them conservative,
// checked on random terrains against the test's own reading of the TIN: for every point p of
// an occluder of top h and every q within ε of p, the terrain at q is at least h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "urbanpvs/geometry/occluders/TerrainOccluders.hpp"

namespace urbanpvs::geometry {
namespace {

constexpr double kNoGround = -std::numeric_limits<double>::infinity();

/// A grid TIN over [x0, x0 + n·d] x [y0, y0 + n·d], two triangles per grid square, heights
/// from f; squares for which `keep` is false are left out (holes in the terrain).
template <class F, class Keep>
Terrain grid_tin(double x0, double y0, double d, int n, F f, Keep keep) {
  Terrain t;
  auto at = [&](int i, int j) {
    const double x = x0 + i * d, y = y0 + j * d;
    return Vec3{x, y, f(x, y)};
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (!keep(i, j)) continue;
      t.triangles.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      t.triangles.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  return t;
}

/// The terrain at p as the test reads the TIN: the highest triangle over p, none outside it.
double terrain_at(const Terrain& t, Vec2 p) {
  double z = kNoGround;
  for (const Triangle3& tr : t.triangles) {
    const Vec2 a{tr.v[0].x, tr.v[0].y}, b{tr.v[1].x, tr.v[1].y}, c{tr.v[2].x, tr.v[2].y};
    const double d = cross(b - a, c - a);
    if (d == 0) continue;
    const double l1 = cross(p - a, c - a) / d, l2 = cross(b - a, p - a) / d, l0 = 1 - l1 - l2;
    if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
    z = std::max(z, l0 * tr.v[0].z + l1 * tr.v[1].z + l2 * tr.v[2].z);
  }
  return z;
}

double area_at(const std::vector<Occluder>& occluders, double top) {
  double a = 0;
  for (const Occluder& o : occluders)
    if (o.top_z == top) a += area(o.shape);
  return a;
}

const auto kAll = [](int, int) { return true; };

/// Six random bumps and dips over about 200 m², as a grid TIN of 3 to 12 m (not aligned with
/// any squares) with 3 % of its grid squares left out as holes.
Terrain random_hilly_tin(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  struct Bump {
    double x, y, r, h;
  };
  std::vector<Bump> bumps;
  for (int k = 0; k < 6; ++k)
    bumps.push_back({200 * u(rng), 200 * u(rng), 20 + 60 * u(rng), -20 + 60 * u(rng)});
  auto f = [&](double x, double y) {
    double z = 0;
    for (const Bump& b : bumps)
      z += b.h * std::exp(-((x - b.x) * (x - b.x) + (y - b.y) * (y - b.y)) / (b.r * b.r));
    return z;
  };
  const double d = 3 + 9 * u(rng), x0 = -7 * u(rng), y0 = -7 * u(rng);
  const int n = static_cast<int>(210 / d);
  std::vector<char> hole(static_cast<std::size_t>(n * n));
  for (char& c : hole) c = u(rng) < 0.03;
  const Terrain t = grid_tin(x0, y0, d, n, f, [&](int i, int j) {
    return hole[static_cast<std::size_t>(j * n + i)] == 0;
  });
  return t;
}

TEST(TerrainOccluders, RampGivesEachLevelWhereItsSquaresReachIt) {
  // z = x / 10 over [0, 100]²: the 4 m square i (x from 4i) has its lowest point 0.4 i high,
  // so level h takes the squares from i = ceil(2.5 h), eroded by 1 m: x from 4 ceil(2.5 h) + 1
  // to 99, y from 1 to 99 (the TIN's border is the ground's end).
  const Terrain t = grid_tin(
      0, 0, 10, 10, [](double x, double) { return x / 10; }, kAll);
  const std::vector<Occluder> occ = terrain_occluders(t, {{0, 0}, {100, 100}}, 1.0, 1.0);
  for (int h = 1; h <= 9; ++h) {
    const double from = 4 * std::ceil(2.5 * h) + 1;
    EXPECT_NEAR(area_at(occ, h), (99 - from) * 98, 1e-6) << "level " << h;
  }
  EXPECT_EQ(area_at(occ, 10), 0.0);  // no square is 10 m high all over
  // Level 0 is the whole square: the ramp rises everywhere above it.
  EXPECT_NEAR(area_at(occ, 0), 98.0 * 98.0, 1e-6);
  for (const Occluder& o : occ) {
    EXPECT_EQ(o.block, kTerrainBlock);
    EXPECT_GT(signed_area2(o.shape.outer), 0) << "outer rings turn counter-clockwise";
  }
}

TEST(TerrainOccluders, FlatGroundIsOneLevelAndNoStepIsNone) {
  // Every level at or below 3 m is the same set: only the highest is kept.
  const Terrain t = grid_tin(
      0, 0, 10, 10, [](double, double) { return 3.0; }, kAll);
  const std::vector<Occluder> occ = terrain_occluders(t, {{0, 0}, {100, 100}}, 1.0, 1.0);
  ASSERT_EQ(occ.size(), 1u);
  EXPECT_EQ(occ[0].top_z, 3.0);
  EXPECT_NEAR(area(occ[0].shape), 98.0 * 98.0, 1e-6);
  EXPECT_TRUE(terrain_occluders(t, {{0, 0}, {100, 100}}, 0.0, 1.0).empty());
  EXPECT_TRUE(terrain_occluders(Terrain{}, {{0, 0}, {100, 100}}, 1.0, 1.0).empty());
}

TEST(TerrainOccluders, AHoleInTheTinHoldsNothingUp) {
  // A flat TIN without its grid square (4, 4): the level is a ring around the hole, at least ε
  // from it, and the hole's ring turns clockwise.
  const Terrain t = grid_tin(
      0, 0, 10, 10, [](double, double) { return 5.0; },
      [](int i, int j) { return i != 4 || j != 4; });
  const std::vector<Occluder> occ = terrain_occluders(t, {{0, 0}, {100, 100}}, 1.0, 1.0);
  ASSERT_EQ(occ.size(), 1u);
  ASSERT_EQ(occ[0].shape.holes.size(), 1u);
  EXPECT_LT(signed_area2(occ[0].shape.holes[0]), 0);
  // Squares 4 m wide: the hole [40, 50]² takes the squares [40, 52]² out (square 12 reaches
  // from 48 to 52), eroded by 1 m: [39, 53]².
  EXPECT_NEAR(area(occ[0].shape), 98.0 * 98.0 - 14.0 * 14.0, 1e-6);
  EXPECT_FALSE(inside(occ[0].shape, Vec2{45, 45}));
  EXPECT_TRUE(inside(occ[0].shape, Vec2{38.5, 45}));
}

TEST(TerrainOccluders, NoOccluderPointHasLowerTerrainWithinEpsilon) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0, 1);
  int checked = 0;
  for (int trial = 0; trial < 6; ++trial) {
    // Random hills on a grid not aligned with the squares, with random holes; steps and ε vary.
    const Terrain t = random_hilly_tin(rng);
    const double step = 0.5 + 4 * u(rng), epsilon = 0.3 + 1.5 * u(rng);
    const std::vector<Occluder> occ = terrain_occluders(t, {{0, 0}, {200, 190}}, step, epsilon);
    ASSERT_FALSE(occ.empty());
    for (const Occluder& o : occ) {
      EXPECT_NEAR(std::remainder(o.top_z, step), 0, 1e-9);
      const Box2 b = o.bounds;
      for (int k = 0; k < 12; ++k) {
        const Vec2 p{b.min.x + (b.max.x - b.min.x) * u(rng),
                     b.min.y + (b.max.y - b.min.y) * u(rng)};
        if (!inside(o.shape, p)) continue;
        // q on the circle of radius ε around p (the farthest it may be) and inside it.
        for (int m = 0; m < 8; ++m) {
          const double a = 2 * std::numbers::pi * u(rng), r = epsilon * (m < 4 ? 1.0 : u(rng));
          const Vec2 q{p.x + r * std::cos(a), p.y + r * std::sin(a)};
          ASSERT_GE(terrain_at(t, q), o.top_z - 1e-9)
              << "trial " << trial << ": terrain at (" << q.x << ", " << q.y << ") below the "
              << "occluder of top " << o.top_z << " at (" << p.x << ", " << p.y << ")";
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 2000);
}

// Sloped squares (terrain_plane_occluders): on a plane ramp every square's top is the ramp
// itself lowered by ε times its slope, exactly; the squares whose ε-surroundings leave the TIN
// are left out.
TEST(TerrainPlaneOccluders, OnARampEachTopIsTheRampLessEpsilonTimesItsSlope) {
  auto ramp = [](double x, double y) { return 3 + 0.3 * x - 0.1 * y; };
  const Terrain t = grid_tin(0, 0, 7, 15, ramp, kAll);  // [0, 105]², not aligned with squares
  const double epsilon = 1.5;
  const std::vector<Occluder> occ = terrain_plane_occluders(t, {{0, 0}, {105, 105}}, 10, epsilon);
  // Squares of 10 m from 0: column k covers [10k, 10k + 10]; within ε of the TIN's rim
  // (0 and 105) are columns 0 and 10 (which reaches 110): 9 x 9 remain.
  ASSERT_EQ(occ.size(), 81u);
  const double drop = epsilon * std::hypot(0.3, 0.1);
  for (const Occluder& o : occ) {
    EXPECT_EQ(o.block, kTerrainBlock);
    EXPECT_NEAR(o.slope.x, 0.3, 1e-9);
    EXPECT_NEAR(o.slope.y, -0.1, 1e-9);
    EXPECT_GE(o.bounds.min.x, 10 - 1e-9);
    EXPECT_LE(o.bounds.max.x, 100 + 1e-9);
    for (const Vec2& p : o.shape.outer) EXPECT_NEAR(o.top_at(p), ramp(p.x, p.y) - drop, 1e-6);
  }
}

// The property that makes them conservative (thesis 7.4, issue 17): for every point p of a
// square and every q within ε of p, the terrain at q is at least the square's top at p. On
// random hills with holes, on grids not aligned with the squares, checked against the test's
// own reading of the TIN. The squares also stay close to the terrain: on average their top at
// a point lies about a metre under it (flat tops at the same squares: three).
TEST(TerrainPlaneOccluders, NoPointOfATopHasLowerTerrainWithinEpsilon) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  int checked = 0;
  double below = 0;
  int below_count = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Terrain t = random_hilly_tin(rng);
    const double square = 4 + 20 * u(rng), epsilon = 0.3 + 1.5 * u(rng);
    const std::vector<Occluder> occ =
        terrain_plane_occluders(t, {{0, 0}, {200, 190}}, square, epsilon);
    ASSERT_GT(occ.size(), 20u);
    for (const Occluder& o : occ) {
      const Box2 b = o.bounds;
      for (int k = 0; k < 6; ++k) {
        const Vec2 p{b.min.x + (b.max.x - b.min.x) * u(rng),
                     b.min.y + (b.max.y - b.min.y) * u(rng)};
        below += terrain_at(t, p) - o.top_at(p);
        ++below_count;
        for (int m = 0; m < 8; ++m) {
          const double a = 2 * std::numbers::pi * u(rng), r = epsilon * (m < 4 ? 1.0 : u(rng));
          const Vec2 q{p.x + r * std::cos(a), p.y + r * std::sin(a)};
          ASSERT_GE(terrain_at(t, q), o.top_at(p) - 1e-9)
              << "trial " << trial << ": terrain at (" << q.x << ", " << q.y << ") below the "
              << "top " << o.top_at(p) << " at (" << p.x << ", " << p.y << ")";
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 20000);
  EXPECT_LT(below / below_count, 1.2);  // 0.87 when written; 2.9 with flat tops
  std::printf("terrain planes: %d points checked, the top %.3f m under the terrain on average\n",
              checked, below / below_count);
}

// A hole in the TIN: no square within ε of it, as around the TIN's rim.
TEST(TerrainPlaneOccluders, NoSquareNearAHoleInTheTin) {
  const Terrain t = grid_tin(
      0, 0, 10, 10, [](double x, double) { return 0.2 * x; },
      [](int i, int j) { return i != 4 || j != 4; });
  const std::vector<Occluder> occ = terrain_plane_occluders(t, {{0, 0}, {100, 100}}, 5, 1);
  // 20 x 20 squares of 5 m; the rim takes the outer ring of them (18 x 18 = 324 left), the
  // hole [40, 50]² the 4 x 4 squares from 35 to 55.
  EXPECT_EQ(occ.size(), 324u - 16u);
  for (const Occluder& o : occ) EXPECT_FALSE(o.bounds.overlaps(Box2{{39.5, 39.5}, {50.5, 50.5}}));
}

}  // namespace
}  // namespace urbanpvs::geometry
