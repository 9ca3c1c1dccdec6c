// SPDX-License-Identifier: GPL-3.0-or-later
// Block fusion and shrunk block occluders (thesis 5.4, 7.3.3), checked against references that
// share no code with CGAL: exact rectangle-union areas by coordinate compression, and point
// sampling of ε-disks against the original footprints.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <set>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/Blocks.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

struct Rect {
  double x0, y0, x1, y1, top;
};

Polygon polygon_of(const Rect& r) {
  return {{{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}}, {}};
}

std::vector<CityObject> objects_of(const std::vector<Rect>& rects) {
  std::vector<CityObject> objects;
  for (const Rect& r : rects) {
    CityObject o;
    o.index = static_cast<std::uint32_t>(objects.size());
    o.source_id = "r" + std::to_string(o.index);
    o.footprint = {polygon_of(r)};
    o.bbox.extend(Vec2{r.x0, r.y0}, 0);
    o.bbox.extend(Vec2{r.x1, r.y1}, r.top);
    o.occluders.push_back({polygon_of(r), 0, r.top});
    objects.push_back(std::move(o));
  }
  return objects;
}

// Exact area of a union of axis-aligned rectangles by coordinate compression.
double rect_union_area(const std::vector<Rect>& rects) {
  std::set<double> xs, ys;
  for (const Rect& r : rects) xs.insert({r.x0, r.x1}), ys.insert({r.y0, r.y1});
  const std::vector<double> X(xs.begin(), xs.end()), Y(ys.begin(), ys.end());
  double total = 0;
  for (std::size_t i = 0; i + 1 < X.size(); ++i)
    for (std::size_t j = 0; j + 1 < Y.size(); ++j) {
      const double cx = 0.5 * (X[i] + X[i + 1]), cy = 0.5 * (Y[j] + Y[j + 1]);
      for (const Rect& r : rects)
        if (r.x0 < cx && cx < r.x1 && r.y0 < cy && cy < r.y1) {
          total += (X[i + 1] - X[i]) * (Y[j + 1] - Y[j]);
          break;
        }
    }
  return total;
}

std::vector<Rect> random_cluster(std::mt19937_64& rng, int n) {
  std::uniform_int_distribution<int> pos(0, 60), size(4, 25), height(3, 12);
  std::vector<Rect> rects;
  for (int i = 0; i < n; ++i) {
    const double x = pos(rng), y = pos(rng);
    rects.push_back({x, y, x + size(rng), y + size(rng), 3.0 * height(rng)});
  }
  return rects;
}

TEST(Union, AreaEqualsExactRectangleUnion) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 300; ++i) {
    const std::vector<Rect> rects = random_cluster(rng, 1 + i % 9);
    std::vector<Polygon> polys;
    for (const Rect& r : rects) polys.push_back(polygon_of(r));
    const std::vector<Polygon> u = union_polygons(polys);
    double a = 0;
    for (const Polygon& p : u) {
      EXPECT_EQ(polygon_defect(p), "");
      a += area(p);
    }
    // Equal, except that points where the union touches itself are pulled 1 µm inwards: never
    // more area than the exact union, and at most a few slivers of 1 µm width less.
    const double exact = rect_union_area(rects);
    EXPECT_LE(a, exact + 1e-9) << "cluster " << i;
    EXPECT_GE(a, exact - 1e-4) << "cluster " << i;
  }
}

TEST(Blocks, SharedWallFusesIntoOneOccluder) {
  // Two houses sharing the wall x = 10 exactly: shrinking them apart would open a 2ε slit.
  const auto objects = objects_of({{0, 0, 10, 8, 12}, {10, 0, 20, 8, 12}});
  const auto blocks = build_blocks(objects, {});
  ASSERT_EQ(blocks.size(), 1u);
  ASSERT_EQ(blocks[0].levels.size(), 1u);
  ASSERT_EQ(blocks[0].levels[0].region.size(), 1u);
  EXPECT_EQ(blocks[0].levels[0].region[0].outer.size(), 4u);  // collinear wall ends removed
  const auto occ = shrink_blocks(blocks, 1.0);
  ASSERT_EQ(occ.size(), 1u);
  // Shrunk by ε and by the outline tolerance, which the simplification may have added.
  const double t = BlockOptions{}.outline_tolerance;
  EXPECT_NEAR(area(occ[0].shape), (18 - 2 * t) * (6 - 2 * t), 1e-9);
}

TEST(Blocks, NearlyCollinearWallsAreSimplifiedAndStayInside) {
  // A row of eight houses whose front and back walls are off by up to 0.4 mm, as shared walls
  // are in real data (coordinates rounded to millimetres, footprints digitized one by one).
  const double jitter[9] = {0.0003, -0.0004, 0.0001, 0.0004, -0.0002, 0.0, -0.0003, 0.0002, 0.0};
  std::vector<Rect> row;
  double low_max = -1, high_min = 1e9;
  for (int i = 0; i < 8; ++i) {
    row.push_back({10.0 * i, jitter[i], 10.0 * (i + 1), 8 + jitter[i + 1], 12});
    low_max = std::max(low_max, jitter[i]);
    high_min = std::min(high_min, 8 + jitter[i + 1]);
  }
  const auto objects = objects_of(row);
  BlockOptions exact;
  exact.outline_tolerance = 0;
  const auto kept = build_blocks(objects, exact);
  const auto simplified = build_blocks(objects, {});
  ASSERT_EQ(kept.size(), 1u);
  ASSERT_EQ(simplified.size(), 1u);
  ASSERT_EQ(simplified[0].levels[0].region.size(), 1u);
  // Every step between two houses is two more vertices unless the tolerance removes it.
  EXPECT_GT(kept[0].levels[0].region[0].outer.size(), 20u);
  EXPECT_LE(simplified[0].levels[0].region[0].outer.size(), 6u);

  // The occluder stays inside every house's eroded footprint: all of it lies in the rectangle
  // that the row certainly covers, shrunk by ε (a polygon whose vertices lie in a convex set
  // lies in it).
  const auto occ = shrink_blocks(simplified, 1.0);
  ASSERT_EQ(occ.size(), 1u);
  for (Vec2 v : occ[0].shape.outer) {
    EXPECT_GE(v.x, 1 - 1e-9);
    EXPECT_LE(v.x, 79 + 1e-9);
    EXPECT_GE(v.y, low_max + 1 - 1e-9);
    EXPECT_LE(v.y, high_min - 1 + 1e-9);
  }
  EXPECT_GT(area(occ[0].shape), 78 * (high_min - low_max - 2) - 0.5);
}

TEST(Blocks, GapToleranceDecidesFusion) {
  const auto near_pair = objects_of({{0, 0, 10, 8, 12}, {10.02, 0, 20, 8, 12}});
  EXPECT_EQ(build_blocks(near_pair, {}).size(), 1u);  // 2 cm digitizing gap: one block
  const auto occ = shrink_blocks(build_blocks(near_pair, {}), 1.0);
  ASSERT_EQ(occ.size(), 1u);
  const auto far_pair = objects_of({{0, 0, 10, 8, 12}, {10.5, 0, 20, 8, 12}});
  EXPECT_EQ(build_blocks(far_pair, {}).size(), 2u);  // a 50 cm passage stays open
  BlockOptions exact;
  exact.gap_tolerance = 0;
  EXPECT_EQ(build_blocks(near_pair, exact).size(), 2u);
}

TEST(Blocks, SteppedLevels) {
  const auto objects = objects_of({{0, 0, 10, 8, 10}, {10, 0, 20, 8, 20}, {100, 0, 110, 8, 5}});
  BlockOptions exact;
  exact.gap_tolerance = 0;
  const auto blocks = build_blocks(objects, exact);
  ASSERT_EQ(blocks.size(), 2u);
  ASSERT_EQ(blocks[0].levels.size(), 2u);
  EXPECT_DOUBLE_EQ(blocks[0].levels[0].top_z, 10);
  EXPECT_DOUBLE_EQ(blocks[0].levels[1].top_z, 20);
  EXPECT_NEAR(area(blocks[0].levels[0].region[0]), 160, 1e-6);  // both houses reach 10 m
  EXPECT_NEAR(area(blocks[0].levels[1].region[0]), 80, 1e-6);   // only the tall one 20 m
  EXPECT_EQ(blocks[0].objects, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(blocks[1].objects, (std::vector<std::uint32_t>{2}));
}

// Every occluder of a level must keep an ε-disk inside footprints that reach that level: no
// occluder is created where no building (tall enough) is. Sampled along the occluder boundary.
TEST(Blocks, RandomClustersOccludersKeepEpsilonInsideBuildings) {
  std::mt19937_64 rng(3);
  BlockOptions exact;
  exact.gap_tolerance = 0;
  int occluders = 0;
  for (int c = 0; c < 200; ++c) {
    const std::vector<Rect> rects = random_cluster(rng, 2 + c % 10);
    const double eps = 0.5 + (c % 4) * 0.5;
    const auto objects = objects_of(rects);
    for (const Occluder& o : shrink_blocks(build_blocks(objects, exact), eps)) {
      ++occluders;
      auto covered = [&](Vec2 q) {
        for (const Rect& r : rects)
          if (r.top >= o.top_z && r.x0 <= q.x && q.x <= r.x1 && r.y0 <= q.y && q.y <= r.y1)
            return true;
        return false;
      };
      for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        for (double t = 0; t <= len; t += 0.25) {
          const Vec2 p = a + (t / len) * (b - a);
          for (int k = 0; k < 16; ++k) {
            const double ang = k * 2 * 3.14159265358979 / 16;
            const Vec2 q{p.x + (eps - 1e-6) * std::cos(ang), p.y + (eps - 1e-6) * std::sin(ang)};
            ASSERT_TRUE(covered(q)) << "cluster " << c << " occluder point (" << p.x << ", " << p.y
                                    << ") is within eps of open ground";
          }
        }
      });
    }
  }
  EXPECT_GT(occluders, 200);
}

}  // namespace
}  // namespace urbanpvs::geometry

namespace urbanpvs::geometry {
namespace {

// On whole cities with the default gap tolerance: around every point of a shrunk occluder, the
// ε-disk lies in footprints reaching the occluder's height, except within the gap tolerance of
// such a footprint (gaps that narrow are closed on purpose).
void check_city_blocks(const std::string& path, const ReadOptions& read) {
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " absent";
  const City city = read_city({path}, read);
  const BlockOptions options;
  const double eps = 1.0;
  struct Foot {
    const Polygon* poly;
    Box2 box;
    double top;
  };
  std::vector<Foot> feet;
  for (const CityObject& o : city.objects)
    for (const OccluderPrism& p : o.occluders)
      feet.push_back({&p.footprint, bounds(p.footprint), p.top_z});
  auto covered = [&](Vec2 q, double top) {
    for (const Foot& f : feet) {
      if (f.top + options.height_step < top ||
          !f.box.grown(options.gap_tolerance).overlaps(Box2{q, q}))
        continue;
      if (inside(*f.poly, q)) return true;
      bool near = false;
      for_each_edge(*f.poly, [&](Vec2 a, Vec2 b) {
        near |= distance_to_segment(q, a, b) <= options.gap_tolerance;
      });
      if (near) return true;
    }
    return false;
  };
  std::size_t samples = 0;
  for (const Occluder& o : shrink_blocks(build_blocks(city.objects, options), eps))
    for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      for (double t = 0; t <= len; t += 0.5) {
        const Vec2 p = a + (t / len) * (b - a);
        for (int k = 0; k < 8; ++k) {
          const double ang = k * 3.14159265358979 / 4;
          const Vec2 q{p.x + (eps - 1e-6) * std::cos(ang), p.y + (eps - 1e-6) * std::sin(ang)};
          ++samples;
          ASSERT_TRUE(covered(q, o.top_z))
              << path << ": occluder point (" << p.x << ", " << p.y << ") at " << o.top_z
              << " m is within eps of open ground";
        }
      }
    });
  EXPECT_GT(samples, 1000u);
}

TEST(Blocks, BundledSampleCity) {
  check_city_blocks(std::string(URBANPVS_SOURCE_DIR) + "/cities/sample/district.city.json", {});
}
TEST(Blocks, DelftCity) {
  check_city_blocks(std::string(URBANPVS_SHARED_CITIES) + "/delft.city.json", {});
}
TEST(Blocks, HelsinkiCity) {
  ReadOptions read;
  read.default_height = 12;
  check_city_blocks(std::string(URBANPVS_SHARED_CITIES) + "/helsinki_buildings.geojson", read);
}

}  // namespace
}  // namespace urbanpvs::geometry
