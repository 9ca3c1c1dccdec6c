// SPDX-License-Identifier: GPL-3.0-or-later
// Repair, don't refuse (issue 11): broken rings become the region they wind around, checked
// against winding numbers computed independently at random points; buildings beyond repair or
// without height stay objects that occlude nothing; --strict refuses instead.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "../../geometry/city/RingRepair.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"

namespace urbanpvs::geometry {
namespace {

const std::filesystem::path kBad = std::filesystem::path(URBANPVS_TEST_DATA) / "bad";

// The winding number of ring r around p (p on no edge), by summing signed angles.
int winding(const Ring& r, Vec2 p) {
  double turn = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i] - p, b = r[(i + 1) % r.size()] - p;
    turn += std::atan2(cross(a, b), dot(a, b));
  }
  return static_cast<int>(std::lround(turn / (2 * M_PI)));
}

double near_edge(const std::vector<Ring>& rings, Vec2 p) {
  double d = INFINITY;
  for (const Ring& r : rings)
    for (std::size_t i = 0; i < r.size(); ++i)
      d = std::min(d, distance_to_segment(p, r[i], r[(i + 1) % r.size()]));
  return d;
}

bool in_pieces(const std::vector<Polygon>& pieces, Vec2 p) {
  for (const Polygon& q : pieces)
    if (inside(q, p)) return true;
  return false;
}

double total_area(const std::vector<Polygon>& pieces) {
  double a = 0;
  for (const Polygon& p : pieces) a += area(p);
  return a;
}

TEST(RingRepair, BowTieBecomesItsTwoTriangles) {
  const std::vector<Polygon> pieces = detail::fill_by_winding({{{0, 0}, {4, 0}, {0, 2}, {4, 2}}});
  ASSERT_EQ(pieces.size(), 2u);
  // Two triangles of base 4 and height 1 meeting at (2, 1), where the union pulls them 1 µm
  // apart.
  EXPECT_NEAR(total_area(pieces), 4.0, 1e-4);
  for (const Polygon& p : pieces) EXPECT_EQ(polygon_defect(p), "");
}

TEST(RingRepair, SpikeAndRepeatedPointsVanish) {
  // A 10 x 10 square with a zero-width spike out of its top edge.
  const Ring r{{0, 0}, {10, 0}, {10, 10}, {6, 10}, {6, 15}, {6, 10}, {0, 10}, {0, 0}};
  const std::vector<Polygon> pieces = detail::fill_by_winding({r});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(area(pieces[0]), 100.0, 1e-9);
  EXPECT_EQ(polygon_defect(pieces[0]), "");
}

TEST(RingRepair, HoleCrossingItsOuterRingIsCutOut) {
  const Ring outer{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const Ring hole{{5, 2}, {15, 2}, {15, 8}, {5, 8}};  // half outside
  const std::vector<Polygon> pieces = detail::fill_by_winding({outer, hole});
  EXPECT_NEAR(total_area(pieces), 100.0 - 30.0, 1e-9);
  for (const Polygon& p : pieces) EXPECT_EQ(polygon_defect(p), "");
}

// Property: for random self-intersecting rings with random holes, a point lies in the repaired
// pieces exactly when the outer ring winds around it and no hole does.
TEST(RingRepair, AgreesWithWindingNumbersOnRandomRings) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 100);
  std::size_t points = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Ring> rings(1 + trial % 3);
    for (std::size_t k = 0; k < rings.size(); ++k) {
      const int n = 4 + trial % 9;
      for (int i = 0; i < n; ++i) rings[k].push_back({u(rng), u(rng)});
    }
    const std::vector<Polygon> pieces = detail::fill_by_winding(rings);
    for (const Polygon& p : pieces) ASSERT_EQ(polygon_defect(p), "") << "trial " << trial;
    for (int i = 0; i < 200; ++i) {
      const Vec2 p{u(rng), u(rng)};
      if (near_edge(rings, p) < 1e-6) continue;
      // The holes count together, each turned to run counter-clockwise by its signed area.
      int holes = 0;
      for (std::size_t k = 1; k < rings.size(); ++k)
        holes += (signed_area2(rings[k]) >= 0 ? 1 : -1) * winding(rings[k], p);
      const bool expect = winding(rings[0], p) != 0 && holes == 0;
      ASSERT_EQ(in_pieces(pieces, p), expect) << "trial " << trial << " at " << p.x << "," << p.y;
      ++points;
    }
  }
  EXPECT_GT(points, 30000u);
}

TEST(CleanPolygon, RepairsAreReportedAndStrictRefusesThem) {
  ReadReport report;
  const Ring bowtie{{0, 0}, {4, 0}, {0, 2}, {4, 2}};
  const std::vector<Polygon> pieces = clean_polygon({bowtie}, {"f.json", "b7", true}, report);
  EXPECT_EQ(pieces.size(), 2u);
  ASSERT_EQ(report.repairs.size(), 1u);
  EXPECT_NE(
      report.repairs[0].find("f.json: b7: outer ring: ring has zero area (ring intersects itself"),
      std::string::npos)
      << report.repairs[0];
  EXPECT_NE(report.repairs[0].find("2 simple pieces, 4.00 m2"), std::string::npos)
      << report.repairs[0];
  try {
    clean_polygon({bowtie}, {"f.json", "b7", true, /*strict=*/true}, report);
    FAIL() << "strict accepted a bow-tie";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::InvalidGeometry);
    EXPECT_EQ(e.feature(), "b7");
  }
  // A valid ring is left as it is and reports nothing.
  ReadReport quiet;
  EXPECT_EQ(clean_polygon({{{0, 0}, {1, 0}, {1, 1}}}, {"f.json", "ok", true}, quiet).size(), 1u);
  EXPECT_TRUE(quiet.repairs.empty());
}

const CityObject& object(const City& c, const std::string& id) {
  for (const CityObject& o : c.objects)
    if (o.source_id == id) return o;
  throw std::runtime_error("no object " + id);
}

TEST(RepairReading, BowTieBuildingIsRepairedAndStillOccludes) {
  const City c = read_city({(kBad / "geojson_bowtie.geojson").string()});
  const CityObject& o = object(c, "way/1001");
  EXPECT_TRUE(o.occludes);
  EXPECT_EQ(o.footprint.size(), 2u);
  EXPECT_EQ(o.occluders.size(), 2u);
  ASSERT_EQ(c.report.repairs.size(), 1u);
  EXPECT_NE(c.report.repairs[0].find("way/1001"), std::string::npos);
}

TEST(RepairReading, ZeroAreaBuildingIsAnObjectThatOccludesNothing) {
  const City c = read_city({(kBad / "geojson_zero_area.geojson").string()});
  ASSERT_EQ(c.objects.size(), 1u);
  const CityObject& o = object(c, "way/1002");
  EXPECT_FALSE(o.occludes);
  EXPECT_TRUE(o.occluders.empty());
  EXPECT_GT(o.bbox.xy.area(), 0);  // its coordinates' box: tested for visibility there
  ASSERT_EQ(c.report.non_occluding.size(), 1u);
  EXPECT_NE(c.report.non_occluding[0].find("way/1002"), std::string::npos);
}

TEST(RepairReading, BuildingWithoutHeightIsTestedAsTallAsItMayBe) {
  ReadOptions options;
  options.max_height = 300;
  const City c = read_city({(kBad / "geojson_missing_height.geojson").string()}, options);
  ASSERT_EQ(c.objects.size(), 2u);
  const CityObject& o = object(c, "relation/777");
  EXPECT_FALSE(o.occludes);
  EXPECT_TRUE(o.occluders.empty());
  EXPECT_EQ(o.bbox.zmax, 300);
  EXPECT_EQ(o.footprint.size(), 1u);  // its own outline still keeps cells out
  EXPECT_TRUE(object(c, "way/4253124").occludes);
  options.strict = true;
  try {
    read_city({(kBad / "geojson_missing_height.geojson").string()}, options);
    FAIL() << "strict accepted a building without height";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::MissingHeight);
  }
}

// A CityJSON building that gives no occluder (here only a LoD0 footprint, its height unknown)
// stands on the convex hull of its positions: a triangle takes half of its box out of free
// space, and is tested for visibility over the whole box, up to --max-height.
TEST(RepairReading, BuildingWithoutOccluderStandsOnTheHullOfItsPositions) {
  const std::string text = R"({"type": "CityJSON", "version": "2.0",
    "transform": {"scale": [0.001, 0.001, 0.001], "translate": [84000, 447000, 0]},
    "metadata": {"referenceSystem": "https://www.opengis.net/def/crs/EPSG/0/7415"},
    "CityObjects": {"wedge": {"type": "Building", "geometry": [
      {"type": "MultiSurface", "lod": "0", "boundaries": [[[0, 1, 2]]]}]}},
    "vertices": [[0, 0, 0], [20000, 0, 0], [0, 20000, 0]]})";
  ReadOptions options;
  options.max_height = 100;
  const City c = read_city_text(text, "wedge.city.json", options);
  ASSERT_EQ(c.objects.size(), 1u);
  const CityObject& o = c.objects[0];
  EXPECT_FALSE(o.occludes);
  EXPECT_NEAR(o.bbox.xy.area(), 400, 1e-6);
  EXPECT_NEAR(o.bbox.zmax - o.ground_z, 100, 1e-9);
  ASSERT_EQ(o.footprint.size(), 1u);
  EXPECT_NEAR(area(o.footprint[0]), 200, 1e-6);
}

// The first defect of a polygon in the order of its edge pairs (i, j), i < j, edges numbered
// outer ring first: an independent reading of polygon_defect's contract with CGAL's exact
// segment predicates (the coordinates below are small integers, so the library's double
// arithmetic is exact too).
std::string first_defect_of_all_pairs(const Polygon& poly) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  struct Edge {
    K::Point_2 a, b;
    std::size_t ring, index, size;
  };
  std::vector<Edge> edges;
  std::vector<const Ring*> rings{&poly.outer};
  for (const Ring& h : poly.holes) rings.push_back(&h);
  for (std::size_t r = 0; r < rings.size(); ++r)
    for (std::size_t i = 0; i < rings[r]->size(); ++i) {
      const Vec2 a = (*rings[r])[i], b = (*rings[r])[(i + 1) % rings[r]->size()];
      edges.push_back({{a.x, a.y}, {b.x, b.y}, r, i, rings[r]->size()});
    }
  auto text = [](const K::Point_2& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", p.x(), p.y());
    return std::string(buf);
  };
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const Edge &e = edges[i], &f = edges[j];
      const bool e_first = e.ring == f.ring && (e.index + 1) % e.size == f.index;
      const bool f_first = e.ring == f.ring && (f.index + 1) % f.size == e.index;
      if (e_first || f_first) {
        const Edge& first = e_first ? e : f;
        const Edge& second = e_first ? f : e;
        // Folding back: the two edges leave their shared vertex in the same direction.
        if (CGAL::collinear(first.a, first.b, second.b) &&
            (first.a - first.b) * (second.b - second.a) > 0)
          return "ring folds back on itself at " + text(first.b);
        continue;
      }
      if (CGAL::do_intersect(K::Segment_2(e.a, e.b), K::Segment_2(f.a, f.b)))
        return (e.ring == f.ring ? "ring intersects itself near "
                                 : "rings intersect each other near ") +
               text(e.a);
    }
  return {};
}

TEST(PolygonDefect, ReportsTheFirstDefectivePairOfRandomPolygons) {
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> k(0, 40);
  std::size_t defective = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    auto ring = [&](int n, int offset) {
      Ring r;
      for (int i = 0; i < n; ++i) r.push_back({double(k(rng) + offset), double(k(rng) + offset)});
      return r;
    };
    Polygon p{ring(3 + trial % 12, 0), {}};
    for (int h = 0; h < trial % 3; ++h) p.holes.push_back(ring(3 + h, 10));
    const std::string want = first_defect_of_all_pairs(p);
    const std::string got = polygon_defect(p);
    // The hole test comes after the pairs: only a polygon without a defective pair gets there.
    if (want.empty())
      ASSERT_TRUE(got.empty() || got == "hole lies outside the outer ring") << "trial " << trial;
    else
      ASSERT_EQ(got, want) << "trial " << trial;
    defective += !want.empty();
  }
  EXPECT_GT(defective, 1000u);  // random rings cross themselves: most trials have several pairs
}

TEST(RepairReading, RealTileWithOneBrokenRingReadsWithTheDefaults) {
  const std::filesystem::path path =
      std::filesystem::path(URBANPVS_SHARED_CITIES) / "tudelft_3dbag_tile5910.city.json";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const City c = read_city({path.string()});
  EXPECT_EQ(c.objects.size(), 432u);
  ASSERT_EQ(c.report.repairs.size(), 1u);
  EXPECT_NE(c.report.repairs[0].find("NL.IMBAG.Pand.0503100000032914-0"), std::string::npos);
  // The three buildings that have only LoD0 footprints (SOURCES.md).
  EXPECT_EQ(c.report.non_occluding.size(), 3u);
  ReadOptions strict;
  strict.strict = true;
  EXPECT_THROW(read_city({path.string()}, strict), InputError);
}

}  // namespace
}  // namespace urbanpvs::geometry
