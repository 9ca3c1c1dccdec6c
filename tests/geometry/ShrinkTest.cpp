// SPDX-License-Identifier: GPL-3.0-or-later
// Property tests of 2D occluder shrinking (thesis 7.3.3): the result must lie inside the
// original and keep at least ε from its boundary, or an object could be marked hidden although
// it is visible from a point within ε of a sample (thesis 7.2).
#include <gtest/gtest.h>

#include <filesystem>

#include "PolygonTestShapes.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"

namespace urbanpvs::geometry {
namespace {

double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  auto orient = [](Vec2 p, Vec2 q, Vec2 r) { return cross(q - p, r - p); };
  const double d1 = orient(a, b, c), d2 = orient(a, b, d), d3 = orient(c, d, a),
               d4 = orient(c, d, b);
  if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0)
    return 0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d),
                   distance_to_segment(c, a, b), distance_to_segment(d, a, b)});
}

// The smallest distance between the boundaries of two polygons. Inside `original` and at least ε
// from its boundary along the whole boundary of `shrunk` means every point of `shrunk` is: the
// distance to a polygon's boundary has no local minimum strictly inside another region.
double boundary_distance(const Polygon& shrunk, const Polygon& original) {
  double best = std::numeric_limits<double>::infinity();
  for_each_edge(shrunk, [&](Vec2 a, Vec2 b) {
    for_each_edge(original,
                  [&](Vec2 c, Vec2 d) { best = std::min(best, segment_distance(a, b, c, d)); });
  });
  return best;
}

// Checks the shrinking contract for one polygon and returns the pieces.
std::vector<Polygon> check_shrink(const Polygon& original, double eps, const std::string& what) {
  const std::vector<Polygon> pieces = shrink_polygon(original, eps);
  const double tol = 1e-7 * (1 + std::sqrt(area(original)));
  for (const Polygon& p : pieces) {
    EXPECT_EQ(polygon_defect(p), "") << what;
    for (Vec2 v : p.outer) EXPECT_TRUE(inside(original, v)) << what << " vertex outside";
    for (const Ring& h : p.holes)
      for (Vec2 v : h) EXPECT_TRUE(inside(original, v)) << what << " hole vertex outside";
    EXPECT_GE(boundary_distance(p, original), eps - tol) << what;
  }
  return pieces;
}

TEST(Shrink, RandomStarPolygonsStayInsideAndEpsilonAway) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> u(0, 1);
  int nonempty = 0;
  for (int i = 0; i < 3000; ++i) {
    const Polygon p = test::random_star_polygon(rng);
    const double eps = 0.1 + 3 * u(rng);
    nonempty += !check_shrink(p, eps, "star #" + std::to_string(i)).empty();
  }
  EXPECT_GT(nonempty, 2000);  // the property is not met by shrinking everything away
}

// For a convex polygon the inward offset is the exact erosion, whose area has a closed form:
// A(ε) = A - P·ε + ε²·Σ cot(αᵢ/2) (αᵢ interior angles), while no edge vanishes.
TEST(Shrink, ConvexAreaMatchesClosedForm) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int compared = 0;
  for (int i = 0; i < 2000; ++i) {
    const Polygon p{test::convex_ring(rng, {500 * u(rng), 500 * u(rng)}, 10 + 50 * u(rng),
                                      3 + int(12 * u(rng))),
                    {}};
    if (p.outer.size() < 3) continue;
    const double eps = 0.05 + 0.5 * u(rng);
    const std::size_t n = p.outer.size();
    std::vector<double> half_cot(n);
    double perimeter = 0, cot_sum = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 e1 = p.outer[(k + n - 1) % n] - p.outer[k], e2 = p.outer[(k + 1) % n] - p.outer[k];
      half_cot[k] = 1 / std::tan(std::atan2(std::abs(cross(e1, e2)), dot(e1, e2)) / 2);
      cot_sum += half_cot[k];
      perimeter += std::hypot(e2.x, e2.y);
    }
    // The closed form holds while no edge collapses: edge k shortens by ε·(cot(αₖ/2)+cot(αₖ₊₁/2)).
    bool collapses = false;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 e = p.outer[(k + 1) % n] - p.outer[k];
      collapses |= std::hypot(e.x, e.y) < eps * (half_cot[k] + half_cot[(k + 1) % n]) + 1e-3;
    }
    if (collapses) continue;
    const std::vector<Polygon> r = check_shrink(p, eps, "convex #" + std::to_string(i));
    ASSERT_EQ(r.size(), 1u);
    const double expected = area(p) - perimeter * eps + eps * eps * cot_sum;
    EXPECT_NEAR(area(r[0]), expected, 1e-6 * area(p)) << "convex #" << i;
    ++compared;
  }
  EXPECT_GT(compared, 200);
}

TEST(Shrink, NarrowPartsVanishAndSplit) {
  // A dumbbell: two 20 m squares joined by a 2 m wide corridor; ε = 1.5 cuts the corridor.
  const Polygon dumbbell{{{0, 0},
                          {20, 0},
                          {20, 9},
                          {40, 9},
                          {40, 0},
                          {60, 0},
                          {60, 20},
                          {40, 20},
                          {40, 11},
                          {20, 11},
                          {20, 20},
                          {0, 20}},
                         {}};
  EXPECT_EQ(check_shrink(dumbbell, 1.5, "dumbbell").size(), 2u);
  EXPECT_EQ(check_shrink(dumbbell, 0.5, "dumbbell").size(), 1u);
  EXPECT_TRUE(check_shrink(dumbbell, 10.5, "dumbbell").empty());
}

TEST(Shrink, CourtyardHoleGrows) {
  const Polygon block{{{0, 0}, {50, 0}, {50, 50}, {0, 50}},
                      {{{15, 15}, {15, 35}, {35, 35}, {35, 15}}}};
  const auto r = check_shrink(block, 1.0, "courtyard");
  ASSERT_EQ(r.size(), 1u);
  ASSERT_EQ(r[0].holes.size(), 1u);
  EXPECT_NEAR(area(r[0]), 48 * 48 - 22 * 22, 1e-9);
}

void check_real_city(const std::string& file, const ReadOptions& options) {
  const std::string path = std::string(URBANPVS_SHARED_CITIES) + "/" + file;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " absent (no ../shared/cities)";
  const City city = read_city({path}, options);
  std::size_t checked = 0;
  for (const CityObject& o : city.objects)
    for (const OccluderPrism& prism : o.occluders)
      for (double eps : {0.5, 1.0, 2.0}) {
        check_shrink(prism.footprint, eps, file + " " + o.source_id);
        ++checked;
      }
  EXPECT_GT(checked, 100u);
}

TEST(Shrink, EveryDelftFootprint) {
  check_real_city("delft.city.json", {});
}
TEST(Shrink, EveryZurichFootprint) {
  check_real_city("zurich_subset_lod2.city.json", {});
}
TEST(Shrink, EveryHelsinkiFootprint) {
  ReadOptions o;
  o.default_height = 12;
  check_real_city("helsinki_buildings.geojson", o);
}

}  // namespace
}  // namespace urbanpvs::geometry
