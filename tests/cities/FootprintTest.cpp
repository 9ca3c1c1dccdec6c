// Footprints: simple polygons, correctly oriented, holes inside, no overlaps between buildings,
// and shared walls with identical vertices between neighbours.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <tuple>

#include "CityTestSupport.hpp"

using namespace citytest;
using urbanpvs::cities::BlockKind;

namespace {

// All edges of a polygon (every ring) as segments.
std::vector<std::pair<P, P>> edges(const std::vector<std::vector<P>>& poly) {
  std::vector<std::pair<P, P>> out;
  for (const auto& r : poly) {
    for (std::size_t i = 0; i < r.size(); ++i) out.emplace_back(r[i], r[(i + 1) % r.size()]);
  }
  return out;
}

// A polygon (with holes) is simple when no two of its edges meet except consecutive edges of
// one ring at their common vertex.
::testing::AssertionResult isSimple(const std::vector<std::vector<P>>& poly) {
  std::vector<std::tuple<P, P, std::size_t, std::size_t>> segs;  // a, b, ring, index
  for (std::size_t r = 0; r < poly.size(); ++r) {
    if (poly[r].size() < 3) return ::testing::AssertionFailure() << "ring with < 3 vertices";
    for (std::size_t i = 0; i < poly[r].size(); ++i) {
      segs.emplace_back(poly[r][i], poly[r][(i + 1) % poly[r].size()], r, i);
    }
  }
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const auto& [a, b, ri, ii] = segs[i];
    if (a == b) return ::testing::AssertionFailure() << "zero-length edge";
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const auto& [c, d, rj, ij] = segs[j];
      const std::size_t n = poly[ri].size();
      const bool adjacent = ri == rj && ((ii + 1) % n == ij || (ij + 1) % n == ii);
      if (adjacent) {
        // Only the shared vertex: the far end of either edge must not lie on the other.
        const P shared = (b == c) ? b : a;
        const P far1 = (a == shared) ? b : a;
        const P far2 = (c == shared) ? d : c;
        if (onSegment(a, b, far2) || onSegment(c, d, far1)) {
          return ::testing::AssertionFailure() << "consecutive edges fold back";
        }
      } else if (segmentsTouch(a, b, c, d)) {
        return ::testing::AssertionFailure()
               << "edges " << ri << ":" << ii << " and " << rj << ":" << ij << " touch";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

void expectValidFootprint(const std::vector<std::vector<P>>& poly, const std::string& id) {
  EXPECT_TRUE(isSimple(poly)) << id;
  EXPECT_GT(twiceArea(poly[0]), 0) << id << ": outer ring must be counter-clockwise";
  for (std::size_t h = 1; h < poly.size(); ++h) {
    EXPECT_LT(twiceArea(poly[h]), 0) << id << ": holes must be clockwise";
    for (const P& p : poly[h]) {
      EXPECT_TRUE(inside({poly[0]}, static_cast<double>(p.x), static_cast<double>(p.y)))
          << id << ": hole vertex outside the outer ring";
    }
  }
}

}  // namespace

TEST(Footprints, AreSimpleAndOriented) {
  for (const City* c : {&oneKm2Lod2(), &city(4.0, 7, RoofMode::Flat)}) {
    for (const auto& b : c->buildings) {
      expectValidFootprint(rings(b.footprint), b.id);
      for (const auto& part : b.parts) expectValidFootprint(rings(part.footprint), part.id);
    }
  }
}

TEST(Footprints, LotsAreConvexAndDisjointFromStreets) {
  for (const auto& blk : oneKm2Flat().blocks) {
    std::vector<P> lot;
    for (const auto& v : blk.lot) lot.push_back(toP(v));
    ASSERT_GE(lot.size(), 3u);
    for (std::size_t i = 0; i < lot.size(); ++i) {
      EXPECT_GT(orient(lot[i], lot[(i + 1) % lot.size()], lot[(i + 2) % lot.size()]), 0)
          << blk.id << " is not strictly convex";
    }
  }
}

// Independent O(n²) check with a bounding-box prefilter: no proper crossing between edges of
// different shapes, and no point just inside one footprint (next to any of its edges) lies
// inside another. Together these rule out any overlap of positive area. Returns a description
// of the first overlap found, or an empty string.
static std::string findOverlap(const City& c, const std::vector<Shape>& shapes,
                               std::size_t* pairs) {
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    for (std::size_t j = i + 1; j < shapes.size(); ++j) {
      if (!shapes[i].bbox.overlaps(shapes[j].bbox)) continue;
      if (pairs != nullptr) ++*pairs;
      const std::string names =
          c.buildings[shapes[i].building].id + " / " + c.buildings[shapes[j].building].id;
      const auto ei = edges(shapes[i].rings);
      const auto ej = edges(shapes[j].rings);
      for (const auto& [a, b] : ei) {
        for (const auto& [cc, d] : ej) {
          if (properlyIntersect(a, b, cc, d)) return "edges cross: " + names;
        }
      }
      // Probe 1 cm inside each edge's midpoint of one shape against the other, both ways.
      for (int way = 0; way < 2; ++way) {
        const Shape& s = way == 0 ? shapes[i] : shapes[j];
        const Shape& o = way == 0 ? shapes[j] : shapes[i];
        for (const auto& [a, b] : edges(s.rings)) {
          const double dx = static_cast<double>(b.x - a.x);
          const double dy = static_cast<double>(b.y - a.y);
          const double len = std::sqrt(dx * dx + dy * dy);
          // Interior is to the left of every edge (outer CCW, holes CW).
          const double px = 0.5 * static_cast<double>(a.x + b.x) - dy / len * 10.0;
          const double py = 0.5 * static_cast<double>(a.y + b.y) + dx / len * 10.0;
          if (inside(o.rings, px, py)) return "interior overlap: " + names;
        }
      }
    }
  }
  return {};
}

TEST(Footprints, NoTwoFootprintsOverlap) {
  for (const City* c : {&oneKm2Lod2(), &city(2.0, 11, RoofMode::Flat)}) {
    const std::vector<Shape> shapes = groundShapes(*c);
    std::size_t pairs = 0;
    EXPECT_EQ(findOverlap(*c, shapes, &pairs), "");
    EXPECT_GT(pairs, shapes.size() / 2);  // neighbours do get compared
  }
}

// The checker itself must catch overlaps: nudge one building 1 m into its neighbour, or stack a
// copy exactly on top of another (no edge crossings at all, only the interior probe sees it).
TEST(Footprints, OverlapCheckerCatchesOverlaps) {
  const City& c = oneKm2Flat();
  const std::vector<Shape> shapes = groundShapes(c);
  std::size_t victim = 0;
  while (c.blocks[c.buildings[shapes[victim].building].block].building_count < 3) ++victim;
  std::vector<Shape> nudged = shapes;
  for (auto& ring : nudged[victim].rings) {
    for (P& p : ring) p.x += 1000;
  }
  nudged[victim].bbox = box(nudged[victim].rings);
  EXPECT_NE(findOverlap(c, nudged, nullptr), "");
  std::vector<Shape> stacked = shapes;
  stacked.push_back(shapes[victim]);
  EXPECT_NE(findOverlap(c, stacked, nullptr), "");
}

// Neighbouring buildings of a block share walls with identical coordinates: a directed edge of
// one footprint appears reversed in a neighbour's.
TEST(Footprints, NeighboursShareWallsExactly) {
  const City& c = oneKm2Flat();
  std::map<std::pair<P, P>, std::size_t> owner;
  const std::vector<Shape> shapes = groundShapes(c);
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    for (const auto& e : edges(shapes[k].rings)) owner[e] = k;
  }
  std::size_t sharing = 0;
  std::size_t in_multi_building_blocks = 0;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const auto& b = c.buildings[shapes[k].building];
    if (c.blocks[b.block].building_count < 2) continue;
    ++in_multi_building_blocks;
    bool shares = false;
    for (const auto& [a, bb] : edges(shapes[k].rings)) {
      const auto it = owner.find({bb, a});
      if (it != owner.end() && it->second != k) {
        shares = true;
        EXPECT_EQ(c.buildings[shapes[it->second].building].block, b.block);
      }
    }
    sharing += shares ? 1 : 0;
  }
  // Every building of a multi-building block shares at least one wall.
  EXPECT_EQ(sharing, in_multi_building_blocks);
  EXPECT_GT(sharing, c.buildings.size() / 2);
}

TEST(Footprints, BuildingsStayOnTheirLot) {
  const City& c = oneKm2Flat();
  for (const auto& b : c.buildings) {
    std::vector<P> lot;
    for (const auto& v : c.blocks[b.block].lot) lot.push_back(toP(v));
    for (const auto& p : b.footprint.outer) {
      const P q = toP(p);
      // Inside or on the boundary of the convex lot (within a millimetre of rounding).
      for (std::size_t i = 0; i < lot.size(); ++i) {
        const P a = lot[i];
        const P bb = lot[(i + 1) % lot.size()];
        const double len =
            std::hypot(static_cast<double>(bb.x - a.x), static_cast<double>(bb.y - a.y));
        EXPECT_GE(static_cast<double>(orient(a, bb, q)) / len, -1.0) << b.id;
      }
    }
  }
}
