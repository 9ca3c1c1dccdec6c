// Determinism, scale, variety and the river of the generated cities.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <stdexcept>

#include "CityTestSupport.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/cities/GeoJsonWriter.hpp"
#include "urbanpvs/cities/Random.hpp"

using namespace citytest;
using urbanpvs::cities::BlockKind;
using urbanpvs::cities::RoofKind;

TEST(CityGenerator, SameParametersGiveIdenticalBytes) {
  CityParams p;
  p.size_km2 = 0.5;
  p.seed = 99;
  p.roofs = RoofMode::Lod2;
  const City a = urbanpvs::cities::generateCity(p);
  const City b = urbanpvs::cities::generateCity(p);
  EXPECT_EQ(urbanpvs::cities::cityJsonText(a), urbanpvs::cities::cityJsonText(b));
  EXPECT_EQ(urbanpvs::cities::geoJsonText(a), urbanpvs::cities::geoJsonText(b));
}

TEST(CityGenerator, DifferentSeedGivesDifferentCity) {
  CityParams p;
  p.size_km2 = 0.5;
  p.seed = 99;
  const std::string a = urbanpvs::cities::cityJsonText(urbanpvs::cities::generateCity(p));
  p.seed = 100;
  const std::string b = urbanpvs::cities::cityJsonText(urbanpvs::cities::generateCity(p));
  EXPECT_NE(a, b);
}

TEST(CityGenerator, RandomStreamIsFixed) {
  // The PRNG's output is part of the output format: pin the first values (SplitMix64 of 0 is
  // the published reference value 0xE220A8397B1DCDAF).
  urbanpvs::cities::Random rng(0);
  EXPECT_EQ(rng.nextU64(), 0xE220A8397B1DCDAFull);
  urbanpvs::cities::Random r2(42);
  const double u = r2.uniform01();
  EXPECT_GE(u, 0.0);
  EXPECT_LT(u, 1.0);
  for (int i = 0; i < 1000; ++i) EXPECT_LT(r2.below(7), 7u);
}

TEST(CityGenerator, Lod2CityIsTheFlatCityWithRoofs) {
  const City& flat = oneKm2Flat();
  const City& lod2 = oneKm2Lod2();
  ASSERT_EQ(flat.buildings.size(), lod2.buildings.size());
  for (std::size_t i = 0; i < flat.buildings.size(); ++i) {
    EXPECT_EQ(flat.buildings[i].id, lod2.buildings[i].id);
    EXPECT_EQ(rings(flat.buildings[i].footprint), rings(lod2.buildings[i].footprint));
    EXPECT_EQ(flat.buildings[i].eaves_height, lod2.buildings[i].eaves_height);
  }
}

// --hills: the same city on a relief that spans exactly `hills`, each building's floor at or
// below the TIN everywhere under its footprint (checked at the footprint's corners and on a
// lattice inside its box, interpolating the grid's two triangles per square independently of
// the generator), its solid raised by its ground, and its heights above the ground unchanged.
TEST(CityGenerator, HillyBuildingsStandOnTheTerrainNeverAboveIt) {
  CityParams p;
  p.size_km2 = 0.25;
  p.seed = 3;
  const City flat = urbanpvs::cities::generateCity(p);
  EXPECT_TRUE(flat.terrain.empty());
  p.hills = 50;
  const City hilly = urbanpvs::cities::generateCity(p);
  const urbanpvs::cities::Terrain& t = hilly.terrain;
  ASSERT_FALSE(t.empty());
  const auto [lo, hi] = std::minmax_element(t.heights.begin(), t.heights.end());
  EXPECT_DOUBLE_EQ(*lo, 0.0);
  EXPECT_NEAR(*hi, 50.0, 1e-3);
  auto tin = [&](double x, double y) {
    const double u = (x - t.origin.x) / t.spacing, v = (y - t.origin.y) / t.spacing;
    const int i = int(u), j = int(v);
    const double fu = u - i, fv = v - j;
    const double a = t.at(i, j), b = t.at(i + 1, j), c = t.at(i + 1, j + 1), d = t.at(i, j + 1);
    // Split along the south-west to north-east diagonal.
    return fu >= fv ? a + fu * (b - a) + fv * (c - b) : a + fv * (d - a) + fu * (c - d);
  };
  ASSERT_EQ(flat.buildings.size(), hilly.buildings.size());
  double lowest = 1e9, highest = -1e9;
  for (std::size_t k = 0; k < hilly.buildings.size(); ++k) {
    const auto& b = hilly.buildings[k];
    EXPECT_EQ(b.eaves_height, flat.buildings[k].eaves_height);
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (const auto& q : b.footprint.outer) {
      EXPECT_LE(b.ground_z, tin(q.x, q.y) + 1e-9) << b.id;
      x0 = std::min(x0, q.x), y0 = std::min(y0, q.y), x1 = std::max(x1, q.x),
      y1 = std::max(y1, q.y);
    }
    for (double y = y0; y <= y1; y += 2)
      for (double x = x0; x <= x1; x += 2) EXPECT_LE(b.ground_z, tin(x, y) + 1e-9) << b.id;
    const auto& solid = b.parts.empty() ? b.solid : b.parts.front().solid;
    double zmin = 1e9;
    for (const auto& v : solid.vertices) zmin = std::min(zmin, v.z);
    EXPECT_NEAR(zmin, b.ground_z, 1e-9) << b.id;
    lowest = std::min(lowest, b.ground_z), highest = std::max(highest, b.ground_z);
  }
  EXPECT_GT(highest - lowest, 20);  // the buildings follow the hills
  const std::string text = urbanpvs::cities::cityJsonText(hilly);
  EXPECT_NE(text.find("\"terrain\":{\"type\":\"TINRelief\""), std::string::npos);
  EXPECT_NE(text.find(", hills 50.000 m\""), std::string::npos);
  EXPECT_EQ(urbanpvs::cities::cityJsonText(urbanpvs::cities::generateCity(p)), text);
}

TEST(CityGenerator, CountsScaleWithSize) {
  const City& quarter = city(0.25, 7, RoofMode::Flat);
  const City& one = oneKm2Flat();
  const City& four = city(4.0, 7, RoofMode::Flat);
  EXPECT_GE(one.buildings.size(), 600u);
  EXPECT_LE(one.buildings.size(), 2000u);
  EXPECT_GE(one.blocks.size(), 150u);
  const double r4 = static_cast<double>(four.buildings.size()) / one.buildings.size();
  const double r1 = static_cast<double>(one.buildings.size()) / quarter.buildings.size();
  EXPECT_GT(r4, 3.0);
  EXPECT_LT(r4, 5.0);
  EXPECT_GT(r1, 3.0);
  EXPECT_LT(r1, 5.5);
}

TEST(CityGenerator, BlocksAreVaried) {
  const City& c = city(4.0, 7, RoofMode::Flat);
  std::set<BlockKind> kinds;
  std::size_t with_holes = 0;
  std::size_t composite = 0;
  std::size_t single_courtyard_buildings = 0;
  for (const auto& blk : c.blocks) {
    kinds.insert(blk.kind);
    EXPECT_LE(blk.building_count, 12u) << blk.id;
    if (blk.kind == BlockKind::Park) {
      EXPECT_EQ(blk.building_count, 0u);
    } else {
      EXPECT_GE(blk.building_count, 1u) << blk.id;
    }
    if (blk.kind == BlockKind::Perimeter && blk.building_count == 1) ++single_courtyard_buildings;
  }
  for (const auto& b : c.buildings) {
    with_holes += b.footprint.holes.empty() ? 0 : 1;
    composite += b.parts.empty() ? 0 : 1;
  }
  EXPECT_EQ(kinds.size(), 4u);
  EXPECT_GT(with_holes, 50u);
  EXPECT_GT(composite, 3u);
  EXPECT_GT(single_courtyard_buildings, 3u);
}

TEST(CityGenerator, HeightsAreInRange) {
  std::size_t towers = 0;
  for (const auto& b : oneKm2Lod2().buildings) {
    EXPECT_EQ(b.ground_z, 0.0);
    EXPECT_GE(b.levels, 1);
    if (b.eaves_height > 35.0) {
      ++towers;
      EXPECT_LE(b.eaves_height, 80.0) << b.id;
      EXPECT_GE(b.eaves_height, 40.0) << b.id;
    } else {
      EXPECT_GE(b.eaves_height, 8.0) << b.id;
      EXPECT_LE(b.eaves_height, 30.0) << b.id;
    }
  }
  EXPECT_GT(towers, 0u);
}

TEST(CityGenerator, IdsAreUniqueAndStable) {
  const std::regex pattern("blk[0-9]{4,}-b[0-9]{2}");
  std::set<std::string> ids;
  for (const auto& b : oneKm2Flat().buildings) {
    EXPECT_TRUE(std::regex_match(b.id, pattern)) << b.id;
    EXPECT_TRUE(ids.insert(b.id).second) << b.id;
    EXPECT_EQ(b.id.substr(0, b.id.find('-')), oneKm2Flat().blocks[b.block].id);
    for (const auto& part : b.parts) EXPECT_TRUE(ids.insert(part.id).second) << part.id;
  }
}

TEST(CityGenerator, RiverIsALongOpenStrip) {
  for (const City* c : {&oneKm2Flat(), &city(4.0, 7, RoofMode::Flat)}) {
    const auto& r = c->river;
    EXPECT_GE(r.water_width, 40.0);
    EXPECT_LE(r.water_width, 80.0);
    EXPECT_GT(r.open_width, r.water_width);
    const double dx = r.to.x - r.from.x;
    const double dy = r.to.y - r.from.y;
    const double len = std::sqrt(dx * dx + dy * dy);
    EXPECT_GE(len, c->side * 0.99);  // crosses the whole city
    // No vertex of any footprint within the band, and every building on one bank.
    const double nx = -dy / len;
    const double ny = dx / len;
    for (const auto& b : c->buildings) {
      int bank = 0;
      for (const auto& p : b.footprint.outer) {
        const double s = nx * (p.x - r.from.x) + ny * (p.y - r.from.y);
        EXPECT_GE(std::fabs(s), 0.5 * r.open_width - 0.001) << b.id;
        const int this_bank = s > 0 ? 1 : -1;
        if (bank != 0) {
          EXPECT_EQ(bank, this_bank) << b.id;
        }
        bank = this_bank;
      }
    }
  }
}

TEST(CityGenerator, EverythingIsInsideTheCitySquare) {
  const City& c = oneKm2Flat();
  for (const auto& b : c.buildings) {
    for (const auto& p : b.footprint.outer) {
      EXPECT_GE(p.x, 0.0);
      EXPECT_GE(p.y, 0.0);
      EXPECT_LE(p.x, c.side);
      EXPECT_LE(p.y, c.side);
    }
  }
}

TEST(CityGenerator, RejectsBadParameters) {
  CityParams p;
  p.size_km2 = 0.0;
  EXPECT_THROW(urbanpvs::cities::generateCity(p), std::invalid_argument);
  p.size_km2 = 1000.0;
  EXPECT_THROW(urbanpvs::cities::generateCity(p), std::invalid_argument);
  p.size_km2 = std::nan("");
  EXPECT_THROW(urbanpvs::cities::generateCity(p), std::invalid_argument);
  p.size_km2 = 1.0;
  p.origin_x = 1e12;
  EXPECT_THROW(urbanpvs::cities::generateCity(p), std::invalid_argument);
}

TEST(CityGenerator, TinyCityStillWorks) {
  CityParams p;
  p.size_km2 = CityParams::kMinSizeKm2;
  p.roofs = RoofMode::Lod2;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    p.seed = seed;
    const City c = urbanpvs::cities::generateCity(p);
    EXPECT_NEAR(c.side, 316.228, 1e-3);
    EXPECT_GT(c.buildings.size(), 10u) << "seed " << seed;
    EXPECT_FALSE(urbanpvs::cities::cityJsonText(c).empty());
  }
}
