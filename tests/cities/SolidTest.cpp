// Building solids: closed, outward-oriented, planar faces; LoD2 roofs with ridge above eaves.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "CityTestSupport.hpp"

using namespace citytest;
using urbanpvs::cities::Face;
using urbanpvs::cities::RoofKind;
using urbanpvs::cities::Solid;
using urbanpvs::cities::SurfaceType;
using urbanpvs::cities::Vec3;

namespace {

// Every directed edge used exactly once, and its reverse exactly once.
::testing::AssertionResult isClosed(const Solid& s) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (const Face& f : s.faces) {
    for (const auto& ring : f.rings) {
      if (ring.size() < 3) return ::testing::AssertionFailure() << "ring with < 3 vertices";
      for (std::size_t i = 0; i < ring.size(); ++i) {
        if (ring[i] >= s.vertices.size()) return ::testing::AssertionFailure() << "bad index";
        ++count[{ring[i], ring[(i + 1) % ring.size()]}];
      }
    }
  }
  for (const auto& [e, n] : count) {
    if (n != 1) return ::testing::AssertionFailure() << "edge used " << n << " times one way";
    const auto rev = count.find({e.second, e.first});
    if (rev == count.end() || rev->second != 1) {
      return ::testing::AssertionFailure()
             << "edge " << e.first << "-" << e.second << " has no opposite";
    }
  }
  return ::testing::AssertionSuccess();
}

// Newell normal of a ring (not normalised): its length is twice the ring's area.
Vec3 newell(const Solid& s, const std::vector<std::uint32_t>& ring) {
  Vec3 n{0, 0, 0};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec3& a = s.vertices[ring[i]];
    const Vec3& b = s.vertices[ring[(i + 1) % ring.size()]];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

// Signed volume by the divergence theorem: positive when faces point outwards.
double signedVolume(const Solid& s) {
  double v = 0.0;
  for (const Face& f : s.faces) {
    for (const auto& ring : f.rings) {
      const Vec3& o = s.vertices[ring[0]];
      for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
        const Vec3& a = s.vertices[ring[i]];
        const Vec3& b = s.vertices[ring[i + 1]];
        v += (o.x * (a.y * b.z - a.z * b.y) - o.y * (a.x * b.z - a.z * b.x) +
              o.z * (a.x * b.y - a.y * b.x)) /
             6.0;
      }
    }
  }
  return v;
}

// Largest distance of a face's vertices from the plane through its centroid with its normal.
double planarityError(const Solid& s, const Face& f) {
  const Vec3 n = newell(s, f.rings[0]);
  const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  Vec3 c{0, 0, 0};
  for (const auto i : f.rings[0]) {
    c.x += s.vertices[i].x / f.rings[0].size();
    c.y += s.vertices[i].y / f.rings[0].size();
    c.z += s.vertices[i].z / f.rings[0].size();
  }
  double worst = 0.0;
  for (const auto& ring : f.rings) {
    for (const auto i : ring) {
      const Vec3& p = s.vertices[i];
      worst = std::max(worst,
                       std::fabs((p.x - c.x) * n.x + (p.y - c.y) * n.y + (p.z - c.z) * n.z) / len);
    }
  }
  return worst;
}

struct Volume {
  std::string id;
  const urbanpvs::cities::Polygon* footprint;
  double ground;
  double eaves;
  double ridge;
  RoofKind roof;
  const Solid* solid;
};

std::vector<Volume> volumes(const City& c) {
  std::vector<Volume> out;
  for (const auto& b : c.buildings) {
    if (b.parts.empty()) {
      out.push_back(
          {b.id, &b.footprint, b.ground_z, b.eaves_height, b.ridge_height, b.roof, &b.solid});
    }
    for (const auto& p : b.parts) {
      out.push_back(
          {p.id, &p.footprint, b.ground_z, p.eaves_height, p.ridge_height, p.roof, &p.solid});
    }
  }
  return out;
}

void expectGoodSolid(const Volume& v) {
  const Solid& s = *v.solid;
  ASSERT_FALSE(s.faces.empty()) << v.id;
  EXPECT_TRUE(isClosed(s)) << v.id;
  EXPECT_GT(signedVolume(s), 0.0) << v.id << ": faces must point outwards";
  int ground = 0, wall = 0, roof = 0;
  for (const Face& f : s.faces) {
    EXPECT_LT(planarityError(s, f), 0.005) << v.id;
    const Vec3 n = newell(s, f.rings[0]);
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    switch (f.type) {
      case SurfaceType::Ground:
        ++ground;
        EXPECT_LT(n.z / len, -0.999) << v.id << ": ground faces look down";
        break;
      case SurfaceType::Wall:
        ++wall;
        EXPECT_LT(std::fabs(n.z / len), 1e-3) << v.id << ": walls are vertical";
        break;
      case SurfaceType::Roof:
        ++roof;
        EXPECT_GT(n.z / len, 0.3) << v.id << ": roofs look up";
        break;
    }
  }
  EXPECT_EQ(ground, 1) << v.id;
  EXPECT_GE(wall, 3) << v.id;
  EXPECT_GE(roof, 1) << v.id;
}

}  // namespace

TEST(Solids, FlatSolidsAreClosedPrisms) {
  for (const Volume& v : volumes(oneKm2Flat())) {
    expectGoodSolid(v);
    EXPECT_EQ(v.roof, RoofKind::Flat);
    EXPECT_EQ(v.eaves, v.ridge);
    for (const Vec3& p : v.solid->vertices) {
      EXPECT_TRUE(p.z == v.ground || p.z == v.ground + v.eaves) << v.id;
    }
  }
}

TEST(Solids, Lod2SolidsAreClosedWithRealRoofs) {
  std::map<RoofKind, std::size_t> kinds;
  std::size_t pitched_with_hole = 0;
  for (const Volume& v : volumes(oneKm2Lod2())) {
    expectGoodSolid(v);
    ++kinds[v.roof];
    if (v.roof != RoofKind::Flat) {
      EXPECT_GT(v.ridge, v.eaves + 0.5) << v.id;
      if (!v.footprint->holes.empty()) ++pitched_with_hole;
    }
    // Within the footprint's bounding box, between the ground and the ridge.
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const auto& p : v.footprint->outer) {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
    double top = 0.0;
    for (const Vec3& p : v.solid->vertices) {
      EXPECT_GE(p.x, x0) << v.id;
      EXPECT_LE(p.x, x1) << v.id;
      EXPECT_GE(p.y, y0) << v.id;
      EXPECT_LE(p.y, y1) << v.id;
      EXPECT_GE(p.z, v.ground) << v.id;
      EXPECT_LE(p.z, v.ground + v.ridge) << v.id;
      top = std::max(top, p.z);
    }
    EXPECT_EQ(top, v.ground + v.ridge) << v.id;
    // Walls reach at least the eaves: no vertex of the roof lies below them.
    for (const Face& f : v.solid->faces) {
      if (f.type != SurfaceType::Roof) continue;
      for (const auto i : f.rings[0]) EXPECT_GE(v.solid->vertices[i].z, v.ground + v.eaves) << v.id;
    }
  }
  // Nearly every non-tower building gets a pitched roof; both kinds occur.
  EXPECT_GT(kinds[RoofKind::Gabled], 200u);
  EXPECT_GT(kinds[RoofKind::Hipped], 200u);
  EXPECT_LT(kinds[RoofKind::Flat], (kinds[RoofKind::Gabled] + kinds[RoofKind::Hipped]) / 20);
  EXPECT_GT(pitched_with_hole, 10u);
}

TEST(Solids, Lod2SolidsAcrossSeeds) {
  // Other seeds and sizes exercise other corner angles, river cuts and slivers.
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    for (const Volume& v : volumes(city(0.5, seed, RoofMode::Lod2))) {
      EXPECT_TRUE(isClosed(*v.solid)) << v.id;
      EXPECT_GT(signedVolume(*v.solid), 0.0) << v.id;
      if (v.roof != RoofKind::Flat) {
        EXPECT_GT(v.ridge, v.eaves) << v.id;
      }
    }
  }
}
