// SPDX-License-Identifier: GPL-3.0-or-later
// RingLocator (the view cells' exact point-in-ring test with its strip index) against
// CGAL::bounded_side_2 on random rings of every size, with coordinates on a coarse lattice so
// that points on edges, vertices on the query's ray and horizontal edges come up all the time.
#include <CGAL/Polygon_2_algorithms.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "../../geometry/cells/RingLocator.hpp"

namespace urbanpvs::geometry::detail {
namespace {

using K = RingLocator::K;
using Point = K::Point_2;

CGAL::Bounded_side cgal_side(const Ring& r, const Point& p) {
  std::vector<Point> pts;
  for (Vec2 v : r) pts.emplace_back(v.x, v.y);
  return CGAL::bounded_side_2(pts.begin(), pts.end(), p, K());
}

// A star-shaped ring of n vertices around (0, 0), radii and angles rounded to the lattice.
Ring star(std::mt19937& rng, std::size_t n, double lattice) {
  std::uniform_real_distribution<double> radius(20, 100);
  Ring r;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    const double d = radius(rng);
    const Vec2 v{std::round(d * std::cos(a) / lattice) * lattice,
                 std::round(d * std::sin(a) / lattice) * lattice};
    if (r.empty() || !(v.x == r.back().x && v.y == r.back().y)) r.push_back(v);
  }
  return r;
}

// Random points of the lattice and of the ring's own edges (their ends and midpoints).
std::vector<Point> queries(std::mt19937& rng, const Ring& r, double lattice) {
  std::uniform_int_distribution<int> k(-110, 110);
  std::vector<Point> out;
  for (int i = 0; i < 400; ++i) out.emplace_back(k(rng) * lattice, k(rng) * lattice);
  // At most about 300 vertices of a large ring: CGAL's test walks the whole ring per query.
  const std::size_t step = std::max<std::size_t>(1, r.size() / 300);
  for (std::size_t i = 0; i < r.size(); i += step) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()];
    out.emplace_back(a.x, a.y);
    out.emplace_back(0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
    out.emplace_back(a.x + 1, a.y);  // on the horizontal through a vertex
    out.emplace_back(a.x - 1, a.y);
  }
  return out;
}

void expect_agreement(const Ring& r, const std::vector<Point>& points) {
  const RingLocator locator(r);
  std::size_t sides[3] = {0, 0, 0};
  for (const Point& p : points) {
    const CGAL::Bounded_side want = cgal_side(r, p);
    ASSERT_EQ(locator.side(p), want) << "ring of " << r.size() << " at " << p;
    ++sides[want + 1];
  }
  // Every answer came up: the cases are not all one kind.
  EXPECT_GT(sides[0], 0u);
  EXPECT_GT(sides[1], 0u);
  EXPECT_GT(sides[2], 0u);
}

TEST(RingLocator, AgreesWithCgalOnStarRingsOfEverySize) {
  std::mt19937 rng(3);
  for (std::size_t n : {3, 4, 5, 8, 17, 64, 300, 2000, 12000}) {
    for (double lattice : {1.0, 4.0}) {
      const Ring r = star(rng, n, lattice);
      if (r.size() < 3) continue;
      expect_agreement(r, queries(rng, r, lattice));
    }
  }
}

TEST(RingLocator, AgreesWithCgalOnSelfIntersectingRings) {
  // The crossing rule both use gives the even-odd region of a ring that crosses itself.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> k(-50, 50);
  for (int trial = 0; trial < 200; ++trial) {
    Ring r;
    const int n = 3 + trial % 40;
    for (int i = 0; i < n; ++i) r.push_back({double(k(rng)) * 2, double(k(rng)) * 2});
    const RingLocator locator(r);
    for (const Point& p : queries(rng, r, 1.0))
      ASSERT_EQ(locator.side(p), cgal_side(r, p)) << "trial " << trial << " at " << p;
  }
}

TEST(RingLocator, LongEdgesAcrossManyStrips) {
  // A comb: long vertical teeth span most strips, short steps between them.
  Ring r;
  for (int i = 0; i < 500; ++i) {
    r.push_back({double(4 * i), 0});
    r.push_back({double(4 * i), 1000});
    r.push_back({double(4 * i + 2), 1000});
    r.push_back({double(4 * i + 2), 2});
  }
  r.push_back({2000, 2});
  r.push_back({2000, -10});
  r.push_back({0, -10});
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> x(-4, 4004), y(-20, 2010);
  std::vector<Point> points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(0.5 * x(rng), 0.5 * y(rng));
  expect_agreement(r, points);
}

TEST(RingLocator, DegenerateRingsBoundNothing) {
  const RingLocator empty(Ring{});
  EXPECT_EQ(empty.side(Point(0, 0)), CGAL::ON_UNBOUNDED_SIDE);
  const RingLocator two(Ring{{0, 0}, {1, 1}});
  EXPECT_EQ(two.side(Point(0.5, 0.5)), CGAL::ON_UNBOUNDED_SIDE);
  const RingLocator square(Ring{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_EQ(square.side(Point(std::nan(""), 0.5)), CGAL::ON_UNBOUNDED_SIDE);
  EXPECT_EQ(square.side(Point(0.5, 0.5)), CGAL::ON_BOUNDED_SIDE);
  EXPECT_EQ(square.side(Point(1, 0.5)), CGAL::ON_BOUNDARY);
}

}  // namespace
}  // namespace urbanpvs::geometry::detail
