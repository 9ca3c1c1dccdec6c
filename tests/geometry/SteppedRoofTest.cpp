// SPDX-License-Identifier: GPL-3.0-or-later
// The stepped height field under a part's roof (SteppedRoof.hpp, thesis 7.3.2): exact levels
// on hand-made roofs, and the property that makes it conservative, f never above the real
// surface, checked on random roofs against the test's own planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "urbanpvs/geometry/city/SteppedRoof.hpp"

namespace urbanpvs::geometry {
namespace {

using Rings3 = std::vector<std::vector<Vec3>>;

Polygon rectangle(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}};
}

Polygon plan_of(const std::vector<Vec3>& ring) {
  Polygon p;
  for (const Vec3& v : ring) p.outer.push_back({v[0], v[1]});
  if (signed_area2(p.outer) < 0) std::reverse(p.outer.begin(), p.outer.end());
  return p;
}

RoofFace face(const std::vector<Vec3>& ring) {
  return roof_face({ring}, {plan_of(ring)});
}

double level_area(const std::vector<OccluderPrism>& prisms, double top) {
  double a = 0;
  for (const OccluderPrism& p : prisms)
    if (std::abs(p.top_z - top) < 1e-9) a += area(p.footprint);
  return a;
}

TEST(SteppedRoof, AnnexAndTowerGiveTwoLevels) {
  // An annex roof at 3 m over [0,10]x[0,10] and a tower roof at 12 m over [10,20]x[0,10]: a
  // single prism would stop at 3 m over both; the tower keeps its 12 m (less the 2 cm inset).
  const std::vector<Polygon> base{rectangle(0, 0, 20, 10)};
  const std::vector<RoofFace> faces{face({{0, 0, 3}, {10, 0, 3}, {10, 10, 3}, {0, 10, 3}}),
                                    face({{10, 0, 12}, {20, 0, 12}, {20, 10, 12}, {10, 10, 12}})};
  const auto prisms = stepped_occluders(base, 0, faces, 1.0);
  ASSERT_EQ(prisms.size(), 2u);
  EXPECT_DOUBLE_EQ(level_area(prisms, 3), 200.0);
  EXPECT_NEAR(level_area(prisms, 12), 9.96 * 9.96, 1e-6);
  for (const OccluderPrism& p : prisms) EXPECT_EQ(p.ground_z, 0);
}

TEST(SteppedRoof, GableGivesALevelEveryStepUpToItsRidge) {
  // Eaves at 6 m along y = 0 and y = 10, ridge at 10 m along y = 5: the level at 6 + k lies
  // where |y - 5| <= 5 (1 - k/4), 10 (1 - k/4) m wide, less 2 cm each side.
  const std::vector<Polygon> base{rectangle(0, 0, 10, 10)};
  const std::vector<RoofFace> faces{face({{0, 0, 6}, {10, 0, 6}, {10, 5, 10}, {0, 5, 10}}),
                                    face({{0, 5, 10}, {10, 5, 10}, {10, 10, 6}, {0, 10, 6}})};
  const auto prisms = stepped_occluders(base, 0, faces, 1.0);
  EXPECT_DOUBLE_EQ(level_area(prisms, 6), 100.0);
  for (int k = 1; k <= 3; ++k) {
    // The 1 mm kept below the plane is 1.25 mm in plan on either side.
    const double width = 10 * (1 - k / 4.0) - 0.0025 - 0.04;
    EXPECT_NEAR(level_area(prisms, 6 + k), width * 9.96, 1e-3) << "level " << 6 + k;
  }
  EXPECT_EQ(level_area(prisms, 10), 0.0);
  // Without steps only the eaves remain, as one prism cut at the lowest point did.
  const auto flat = stepped_occluders(base, 0, faces, 0.0);
  ASSERT_EQ(flat.size(), 1u);
  EXPECT_DOUBLE_EQ(flat[0].top_z, 6.0);
}

// The height of the plane through `ring` (Newell's normal, mean vertex) at p, and the largest
// distance of a vertex from that plane: the test's own surface model.
std::pair<double, double> height_at(const std::vector<Vec3>& ring, Vec2 p) {
  Vec3 n{0, 0, 0}, c{0, 0, 0};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec3& a = ring[i];
    const Vec3& b = ring[(i + 1) % ring.size()];
    n += Vec3{(a[1] - b[1]) * (a[2] + b[2]), (a[2] - b[2]) * (a[0] + b[0]),
              (a[0] - b[0]) * (a[1] + b[1])};
    c += a;
  }
  c /= static_cast<double>(ring.size());
  auto z = [&](Vec2 q) { return c[2] - (n[0] * (q.x - c[0]) + n[1] * (q.y - c[1])) / n[2]; };
  double dev = 0;
  for (const Vec3& v : ring) dev = std::max(dev, std::abs(v[2] - z({v[0], v[1]})));
  return {z(p), dev};
}

Vec2 random_point_in(const Polygon& p, std::mt19937& rng) {
  const Box2 b = bounds(p);
  std::uniform_real_distribution<double> ux(b.min.x, b.max.x), uy(b.min.y, b.max.y);
  for (int tries = 0; tries < 1000; ++tries) {
    const Vec2 q{ux(rng), uy(rng)};
    if (inside(p, q)) return q;
  }
  return p.outer.front();
}

TEST(SteppedRoof, RandomRoofsNeverRiseAboveAFaceOverThem) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coord(0, 20), height(3, 25), tilt(-0.8, 0.8);
  for (int city = 0; city < 60; ++city) {
    std::vector<std::vector<Vec3>> rings;
    std::vector<RoofFace> faces;
    for (int k = 0; k < 6; ++k) {
      double x0 = coord(rng), x1 = coord(rng), y0 = coord(rng), y1 = coord(rng);
      if (x1 - x0 < 1 && x0 - x1 < 1) x1 = x0 + 2;
      if (y1 - y0 < 1 && y0 - y1 < 1) y1 = y0 + 2;
      const double z = height(rng), gx = k % 2 ? tilt(rng) : 0, gy = k % 3 ? tilt(rng) : 0;
      std::vector<Vec3> ring;
      for (Vec2 q :
           rectangle(std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)).outer)
        ring.push_back({q.x, q.y, std::max(0.5, z + gx * (q.x - 10) + gy * (q.y - 10))});
      faces.push_back(face(ring));
      rings.push_back(ring);
    }
    const auto prisms = stepped_occluders({rectangle(0, 0, 20, 20)}, 0, faces, 0.5);
    ASSERT_FALSE(prisms.empty());
    for (const OccluderPrism& prism : prisms)
      for (int s = 0; s < 40; ++s) {
        const Vec2 p = random_point_in(prism.footprint, rng);
        for (const auto& ring : rings) {
          if (!inside(plan_of(ring), p)) continue;
          const auto [z, dev] = height_at(ring, p);
          EXPECT_GE(z + dev + 1e-9, prism.top_z) << "city " << city << " at " << p.x << ", " << p.y;
        }
      }
  }
}

}  // namespace
}  // namespace urbanpvs::geometry
