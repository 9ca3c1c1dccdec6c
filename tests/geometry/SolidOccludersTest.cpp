// SPDX-License-Identifier: GPL-3.0-or-later
// Occluder shrinking in 3D (SolidOccluders.hpp, thesis 7.3.1) on solids that are not height
// fields (an arcade, an overhang, a bridge between two towers) and on ones that are (a box, a
// gabled house), checked against the test's own reading of the surfaces: a point is inside
// when a ray from it crosses the faces an odd number of times. For every point p of an
// occluder of top h (down to the ground) and every q within ε of p horizontally, q is inside.
// Where the 2.5D route also applies, the two are compared.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "FaceTriangulation.hpp"
#include "SharedCities.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/geometry/occluders/SolidOccluders.hpp"

namespace urbanpvs::geometry {
namespace {

using Solid = std::vector<Surface3>;
using Profile = std::vector<Vec2>;  // (x, z), counter-clockwise

/// The prism of a counter-clockwise profile in the x-z plane, extruded along y over [0, depth]:
/// its two ends and a quad per profile edge, every face wound counter-clockwise from outside.
Solid extruded_profile(const Profile& profile, double depth) {
  Solid s;
  std::vector<Vec3> front, back;  // front at y = 0 faces -y
  for (const Vec2& p : profile) front.push_back({p.x, 0, p.y});
  for (auto it = profile.rbegin(); it != profile.rend(); ++it)
    back.push_back({it->x, depth, it->y});
  s.push_back({{front}});
  s.push_back({{back}});
  for (std::size_t k = 0; k < profile.size(); ++k) {
    const Vec2 a = profile[k], b = profile[(k + 1) % profile.size()];
    s.push_back({{{{a.x, 0, a.y}, {a.x, depth, a.y}, {b.x, depth, b.y}, {b.x, 0, b.y}}}});
  }
  return s;
}

/// A box [x0, x1] x [y0, y1] x [z0, z1].
Solid box(double x0, double y0, double x1, double y1, double z0, double z1) {
  Solid s = extruded_profile({{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}}, y1 - y0);
  for (Surface3& f : s)
    for (Vec3& v : f.rings.front()) v.y += y0;
  return s;
}

/// A house on [0, 12] x [0, 8]: walls 6 m high, a ridge at 10 m along x over y = 4.
Solid gabled_house() {
  // The gable profile in the y-z plane, extruded along x: build it in x-z and swap x and y.
  Solid s = extruded_profile({{0, 0}, {8, 0}, {8, 6}, {4, 10}, {0, 6}}, 12);
  for (Surface3& f : s) {
    for (Vec3& v : f.rings.front()) std::swap(v.x, v.y);
    std::reverse(f.rings.front().begin(), f.rings.front().end());  // the swap mirrors
  }
  return s;
}

/// Whether p is inside the solid: the parity of the faces a ray from p crosses. The ray's
/// direction is generic, so it meets no edge of these solids.
bool inside(const Solid& solid, Vec3 p) {
  const Vec3 d = glm::normalize(Vec3{0.3141, 0.2718, 0.9101});
  int crossings = 0;
  for (const Surface3& f : solid) {
    const std::vector<Vec3>& r = f.rings.front();
    Vec3 n{0, 0, 0};  // Newell's normal
    for (std::size_t k = 0; k < r.size(); ++k) n += glm::cross(r[k], r[(k + 1) % r.size()]);
    const double dn = glm::dot(n, d);
    if (dn == 0) continue;
    const double t = glm::dot(n, r[0] - p) / dn;
    if (t <= 0) continue;
    const Vec3 q = p + t * d;
    // Point in polygon, in the plane the normal is largest across.
    const int drop = std::abs(n.x) > std::abs(n.y) ? (std::abs(n.x) > std::abs(n.z) ? 0 : 2)
                                                   : (std::abs(n.y) > std::abs(n.z) ? 1 : 2);
    auto uv = [&](const Vec3& v) {
      return drop == 0 ? Vec2{v.y, v.z} : drop == 1 ? Vec2{v.x, v.z} : Vec2{v.x, v.y};
    };
    const Vec2 c = uv(q);
    bool in = false;
    for (std::size_t k = 0, j = r.size() - 1; k < r.size(); j = k++) {
      const Vec2 a = uv(r[k]), b = uv(r[j]);
      if ((a.y > c.y) != (b.y > c.y) && c.x < (b.x - a.x) * (c.y - a.y) / (b.y - a.y) + a.x)
        in = !in;
    }
    if (in) ++crossings;
  }
  return crossings % 2 == 1;
}

/// The thesis 7.4 property at random points of every occluder: the column from just above the
/// ground up to the top, with everything within ε of it horizontally, is inside the solid (as
/// `inside_solid` reads it).
template <class Inside>
void expect_conservative_by(Inside inside_solid, const ShrunkSolid& shrunk, double ground,
                            double epsilon, int points_per_occluder) {
  std::mt19937 rng(7);
  for (const Occluder& o : shrunk.occluders) {
    std::uniform_real_distribution<double> ux(o.bounds.min.x, o.bounds.max.x);
    std::uniform_real_distribution<double> uy(o.bounds.min.y, o.bounds.max.y);
    std::uniform_real_distribution<double> uz(ground + 0.02, o.top_z - 1e-6);
    for (int k = 0; k < points_per_occluder;) {
      const Vec2 p{ux(rng), uy(rng)};
      if (!inside(o.shape, p)) continue;
      ++k;
      const double z = uz(rng);
      for (int a = 0; a < 16; ++a) {
        const double angle = 2 * std::numbers::pi * a / 16;
        const double r = a % 2 == 0 ? epsilon : epsilon * 0.5;
        const Vec3 q{p.x + r * std::cos(angle), p.y + r * std::sin(angle), z};
        ASSERT_TRUE(inside_solid(q))
            << "occluder top " << o.top_z << " at (" << p.x << ", " << p.y << "), z " << z << ": ("
            << q.x << ", " << q.y << ") is outside";
      }
    }
  }
}

void expect_conservative(const Solid& solid, const ShrunkSolid& shrunk, double ground,
                         double epsilon, int points_per_occluder = 60) {
  expect_conservative_by([&](const Vec3& q) { return inside(solid, q); }, shrunk, ground, epsilon,
                         points_per_occluder);
}

/// The same property at the occluders' edges and corners, where a fault would show first: each
/// corner and edge middle moved 0.1 mm inwards (the polygon's inside is left of its edges,
/// holes included), just under the top and just over the ground.
void expect_conservative_at_edges(const Solid& solid, const ShrunkSolid& shrunk, double ground,
                                  double epsilon) {
  for (const Occluder& o : shrunk.occluders) {
    std::vector<const Ring*> rings = {&o.shape.outer};
    for (const Ring& h : o.shape.holes) rings.push_back(&h);
    for (const Ring* r : rings)
      for (std::size_t k = 0; k < r->size(); ++k) {
        const Vec2 a = (*r)[k], b = (*r)[(k + 1) % r->size()];
        const Vec2 along = (b - a) / glm::length(b - a), inward{-along.y, along.x};
        for (const Vec2& p : {a + 1e-4 * (along + inward), (a + b) / 2.0 + 1e-4 * inward})
          for (const double z : {o.top_z - 1e-6, ground + 0.02})
            for (int n = 0; n < 16; ++n) {
              const double angle = 2 * std::numbers::pi * n / 16;
              const Vec3 q{p.x + epsilon * std::cos(angle), p.y + epsilon * std::sin(angle), z};
              ASSERT_TRUE(inside(solid, q))
                  << "occluder top " << o.top_z << " near (" << p.x << ", " << p.y << "), z " << z
                  << ": (" << q.x << ", " << q.y << ") is outside";
            }
      }
  }
}

/// The top of the occluders over p (the ground when none holds it).
double top_at(const ShrunkSolid& s, Vec2 p, double ground) {
  double top = ground;
  for (const Occluder& o : s.occluders)
    if (inside(o.shape, p)) top = std::max(top, o.top_z);
  return top;
}

/// The same levels, each with the same area.
void expect_same_occluders(const ShrunkSolid& got, const ShrunkSolid& expected) {
  ASSERT_EQ(got.occluders.size(), expected.occluders.size());
  for (std::size_t k = 0; k < expected.occluders.size(); ++k) {
    EXPECT_EQ(got.occluders[k].top_z, expected.occluders[k].top_z);
    EXPECT_NEAR(area(got.occluders[k].shape), area(expected.occluders[k].shape), 1e-9);
  }
}

/// The face of `solid` all of whose corners satisfy `on`.
template <class On>
Solid::iterator face_where(Solid& solid, On on) {
  return std::find_if(solid.begin(), solid.end(), [&](const Surface3& f) {
    return std::all_of(f.rings[0].begin(), f.rings[0].end(), on);
  });
}

class SolidOccluders : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!solid_shrinking_available()) GTEST_SKIP() << "built without TetGen (URBANPVS_TETGEN=OFF)";
  }
};

TEST(SolidOccludersBuild, SaysWhenTetGenIsMissing) {
  const ShrunkSolid s = shrink_solid(box(0, 0, 10, 10, 0, 10), 0, 1, 1);
  if (solid_shrinking_available()) {
    EXPECT_TRUE(s.declined.empty()) << s.declined;
  } else {
    EXPECT_EQ(s.declined, "built without TetGen (URBANPVS_TETGEN=OFF)");
    EXPECT_TRUE(s.occluders.empty());
  }
}

TEST_F(SolidOccluders, ABoxGivesItsFootprintErodedByEpsilonAndAQuarter) {
  const Solid solid = box(0, 0, 20, 12, 0, 10);
  const ShrunkSolid s = shrink_solid(solid, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  ASSERT_EQ(s.occluders.size(), 1u);
  EXPECT_EQ(s.occluders[0].top_z, 10);
  // Squares of ε/2 from the box's corner, each kept when ε + a quarter of ε fits around its
  // centre: exactly [1, 19] x [1, 11].
  EXPECT_NEAR(area(s.occluders[0].shape), 18.0 * 10.0, 1e-9);
  EXPECT_NEAR(s.occluders[0].bounds.min.x, 1, 1e-9);
  EXPECT_NEAR(s.occluders[0].bounds.max.y, 11, 1e-9);
  expect_conservative(solid, s, 0, 1);
  expect_conservative_at_edges(solid, s, 0, 1);
}

TEST_F(SolidOccluders, WallsOffTheRasterStayConservative) {
  // The raster starts at the solid's corner: a far wall between two squares' reach, and walls
  // at 30 degrees to it, are where an erosion too small by a tenth would show.
  const Solid off_grid = box(0, 0, 20.45, 12.45, 0, 10);
  const ShrunkSolid a = shrink_solid(off_grid, 0, 1, 1);
  ASSERT_TRUE(a.declined.empty()) << a.declined;
  expect_conservative(off_grid, a, 0, 1);
  expect_conservative_at_edges(off_grid, a, 0, 1);
  Solid turned = extruded_profile(
      {{0, 0}, {12, 0}, {12, 4}, {18, 4}, {18, 0}, {30, 0}, {30, 12}, {0, 12}}, 10);
  const double c = std::cos(std::numbers::pi / 6), s30 = std::sin(std::numbers::pi / 6);
  for (Surface3& f : turned)
    for (Vec3& v : f.rings.front()) v = {c * v.x - s30 * v.y, s30 * v.x + c * v.y, v.z};
  const ShrunkSolid b = shrink_solid(turned, 0, 1, 1);
  ASSERT_TRUE(b.declined.empty()) << b.declined;
  expect_conservative(turned, b, 0, 1, 400);
  expect_conservative_at_edges(turned, b, 0, 1);
}

TEST_F(SolidOccluders, AnArcadeKeepsNothingOverThePassage) {
  // A bar 30 m long, 10 m deep, 12 m high, with a passage 6 m wide and 4 m high under it.
  const Solid solid = extruded_profile(
      {{0, 0}, {12, 0}, {12, 4}, {18, 4}, {18, 0}, {30, 0}, {30, 12}, {0, 12}}, 10);
  const ShrunkSolid s = shrink_solid(solid, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  expect_conservative(solid, s, 0, 1);
  expect_conservative_at_edges(solid, s, 0, 1);
  EXPECT_EQ(top_at(s, {15, 5}, 0), 0) << "the passage is open from the ground up";
  EXPECT_EQ(top_at(s, {11.5, 5}, 0), 0) << "within ε of the passage";
  EXPECT_EQ(top_at(s, {6, 5}, 0), 12);
  EXPECT_EQ(top_at(s, {24, 5}, 0), 12);
}

TEST_F(SolidOccluders, PartsThatMeetInsideAFaceAreShrunkAlone) {
  // The arcade of the test above, and a dormer: a closed box standing on its roof, its floor
  // inside the roof face, which is not cut around it (as Zürich's parts are given).
  const Solid bar = extruded_profile(
      {{0, 0}, {12, 0}, {12, 4}, {18, 4}, {18, 0}, {30, 0}, {30, 12}, {0, 12}}, 10);
  Solid building = bar;
  for (Surface3 f : box(4, 3, 8, 7, 12, 14)) {
    f.part = 1;
    building.push_back(f);
  }
  Solid as_one = building;
  for (Surface3& f : as_one) f.part = 0;
  const ShrunkSolid whole = shrink_solid(as_one, 0, 1, 1);
  EXPECT_TRUE(whole.occluders.empty()) << "the parts' overlapping faces make no solid";
  EXPECT_FALSE(whole.declined.empty());
  const ShrunkSolid s = shrink_solid(building, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  // The dormer holds nothing up from the ground; the bar alone gives what it gives alone.
  expect_conservative(bar, s, 0, 1);
  expect_conservative_at_edges(bar, s, 0, 1);
  EXPECT_EQ(top_at(s, {15, 5}, 0), 0) << "the passage is open from the ground up";
  EXPECT_EQ(top_at(s, {6, 5}, 0), 12);
  EXPECT_EQ(top_at(s, {24, 5}, 0), 12);
  const ShrunkSolid alone = shrink_solid(bar, 0, 1, 1);
  double area_alone = 0, area_parts = 0;
  for (const Occluder& o : alone.occluders) area_alone += area(o.shape);
  for (const Occluder& o : s.occluders) area_parts += area(o.shape);
  EXPECT_NEAR(area_parts, area_alone, 1e-9);
}

TEST_F(SolidOccluders, AnOverhangKeepsTheColumnsUnderTheGroundFloor) {
  // Ground floor x in [0, 10], 4 m high; upper floors overhang to x = 14, up to 12 m.
  const Solid solid = extruded_profile({{0, 0}, {10, 0}, {10, 4}, {14, 4}, {14, 12}, {0, 12}}, 10);
  const ShrunkSolid s = shrink_solid(solid, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  expect_conservative(solid, s, 0, 1);
  expect_conservative_at_edges(solid, s, 0, 1);
  EXPECT_EQ(top_at(s, {5, 5}, 0), 12);
  EXPECT_EQ(top_at(s, {8.5, 5}, 0), 12) << "ε from the ground floor's wall, up to the top";
  EXPECT_EQ(top_at(s, {12, 5}, 0), 0) << "nothing stands under the overhang";
}

TEST_F(SolidOccluders, ABridgeBetweenTwoTowersIsNotGroundStanding) {
  // Two towers 8 m wide, 20 m high, and a closed bridge from 10 to 14 m between them, as one
  // solid with internal faces where the bridge meets the towers.
  Solid solid = box(0, 0, 8, 8, 0, 20);
  for (Surface3& f : box(20, 0, 28, 8, 0, 20)) solid.push_back(f);
  const Solid bridge = box(8, 2, 20, 6, 10, 14);
  // The bridge's end faces lie in the towers' walls: the walls are split around them so that
  // the faces meet edge to edge, as a valid solid's do.
  Solid welded;
  for (const Surface3& f : solid) {
    const std::vector<Vec3>& r = f.rings.front();
    const bool inner_wall =
        std::all_of(r.begin(), r.end(), [](const Vec3& v) { return v.x == 8; }) ||
        std::all_of(r.begin(), r.end(), [](const Vec3& v) { return v.x == 20; });
    if (!inner_wall) {
      welded.push_back(f);
      continue;
    }
    const double x = r[0].x;
    // The wall x = const, y in [0, 8], z in [0, 20] minus the bridge's end y in [2, 6],
    // z in [10, 14], as four quads around it, wound like the wall.
    const bool outward_plus_x = x == 8;
    auto quad = [&](double y0, double y1, double z0, double z1) {
      std::vector<Vec3> q = {{x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}};
      if (!outward_plus_x) std::reverse(q.begin(), q.end());
      welded.push_back({{q}});
    };
    quad(0, 8, 0, 10);
    quad(0, 8, 14, 20);
    quad(0, 2, 10, 14);
    quad(6, 8, 10, 14);
  }
  for (const Surface3& f : bridge) {
    const std::vector<Vec3>& r = f.rings.front();
    const bool end = std::all_of(r.begin(), r.end(), [&](const Vec3& v) { return v.x == r[0].x; });
    if (!end) welded.push_back(f);
  }
  const ShrunkSolid s = shrink_solid(welded, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  expect_conservative(welded, s, 0, 1);
  expect_conservative_at_edges(welded, s, 0, 1);
  EXPECT_EQ(top_at(s, {4, 4}, 0), 20);
  EXPECT_EQ(top_at(s, {24, 4}, 0), 20);
  EXPECT_EQ(top_at(s, {14, 4}, 0), 0) << "under the bridge is open";
}

TEST_F(SolidOccluders, AFaceThatBoundsNoVolumeIsLeftOut) {
  // A LoD0 footprint kept beside the solid, at 0.5 m above its floor: it cuts through the
  // walls, but none of its edges is another face's.
  Solid solid = box(0, 0, 20, 12, -0.5, 10);
  solid.push_back({{{{0, 0, 0}, {20, 0, 0}, {20, 12, 0}, {0, 12, 0}}}});
  const ShrunkSolid s = shrink_solid(solid, -0.5, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  ASSERT_EQ(s.occluders.size(), 1u);
  EXPECT_NEAR(area(s.occluders[0].shape), 18.0 * 10.0, 1e-9);
}

TEST_F(SolidOccluders, AFaceWithAHoleThatAnotherFaceFillsIsClosed) {
  // A roof with a hole over [8, 12] x [4, 8] and a lid in it: a solid like the box.
  Solid solid = box(0, 0, 20, 12, 0, 10);
  const std::vector<Vec3> hole = {{8, 4, 10}, {8, 8, 10}, {12, 8, 10}, {12, 4, 10}};
  Surface3& top = *std::find_if(solid.begin(), solid.end(), [](const Surface3& f) {
    return std::all_of(f.rings[0].begin(), f.rings[0].end(),
                       [](const Vec3& v) { return v.z == 10; });
  });
  top.rings.push_back(hole);
  solid.push_back({{std::vector<Vec3>(hole.rbegin(), hole.rend())}});
  const ShrunkSolid s = shrink_solid(solid, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  ASSERT_EQ(s.occluders.size(), 1u);
  EXPECT_EQ(s.occluders[0].top_z, 10);
  EXPECT_NEAR(area(s.occluders[0].shape), 18.0 * 10.0, 1e-9);
}

TEST_F(SolidOccluders, AnOpenBottomIsClosedOnTheGround) {
  // A house without a ground face, as LoD2 models often come: its walls' bottom edges close.
  Solid solid = gabled_house();
  const auto bottom = face_where(solid, [](const Vec3& v) { return v.z == 0; });
  ASSERT_NE(bottom, solid.end());
  solid.erase(bottom);
  // A LoD0 footprint kept beside it, 20 cm up: it stands alone and caps nothing.
  solid.push_back({{{{0, 0, 0.2}, {12, 0, 0.2}, {12, 8, 0.2}, {0, 8, 0.2}}}});
  const ShrunkSolid open = shrink_solid(solid, 0, 1, 1);
  ASSERT_TRUE(open.declined.empty()) << open.declined;
  const ShrunkSolid closed = shrink_solid(gabled_house(), 0, 1, 1);
  expect_same_occluders(open, closed);
  expect_conservative(gabled_house(), open, 0, 1);
  expect_conservative_at_edges(gabled_house(), open, 0, 1);
  // Open higher up (a roof face missing) it stays open.
  Solid roofless = gabled_house();
  roofless.erase(face_where(roofless, [](const Vec3& v) { return v.z >= 6 && v.y <= 4; }));
  EXPECT_EQ(shrink_solid(roofless, 0, 1, 1).declined, "its faces close no volume");
}

/// The gabled house with its roof reaching `eaves` past every wall, as LoD2 models draw roofs:
/// the walls end inside the roof faces (their tops are edges of the walls only), and the eaves
/// have no underside.
Solid house_with_eaves(double eaves) {
  Solid s = gabled_house();
  std::erase_if(s, [](const Surface3& f) {
    return std::all_of(f.rings[0].begin(), f.rings[0].end(),
                       [](const Vec3& v) { return v.z >= 6; });
  });
  const double x0 = -eaves, x1 = 12 + eaves, low = 6 - eaves;  // the roof falls 1 m per m
  s.push_back({{{{x0, -eaves, low}, {x1, -eaves, low}, {x1, 4, 10}, {x0, 4, 10}}}});
  s.push_back({{{{x1, 8 + eaves, low}, {x0, 8 + eaves, low}, {x0, 4, 10}, {x1, 4, 10}}}});
  return s;
}

TEST_F(SolidOccluders, ARoofThatOverhangsItsWallsIsCutAlongTheirTops) {
  // Before the roof faces were cut along the wall tops, this house closed no volume and gave
  // nothing (43 of Zürich's 49 buildings, README "Shrinking solids in 3D").
  const Solid eaves = house_with_eaves(0.5);
  ASSERT_FALSE(overhangs(eaves, 0)) << "no face looks down: the bake leaves it to the blocks";
  const ShrunkSolid s = shrink_solid(eaves, 0, 1, 1);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  // What closes is the house under its roof: the same occluders as the house without eaves.
  const ShrunkSolid closed = shrink_solid(gabled_house(), 0, 1, 1);
  expect_same_occluders(s, closed);
  expect_conservative(gabled_house(), s, 0, 1, 120);
  expect_conservative_at_edges(gabled_house(), s, 0, 1);
  EXPECT_EQ(top_at(s, {6, -0.25}, 0), 0) << "nothing stands under the eaves";
  // The roof's corners a few millimetres off its plane and the gables' apexes 2 mm off the
  // ridge, as real coordinates are rounded: still cut, still the same.
  Solid rounded = eaves;
  for (Surface3& f : rounded)
    for (Vec3& v : f.rings[0])
      if (v.z == 10 && (v.x == 0 || v.x == 12)) v.y += 0.002;
  rounded[rounded.size() - 2].rings[0][0].z -= 0.003;
  const ShrunkSolid r = shrink_solid(rounded, 0, 1, 1);
  ASSERT_TRUE(r.declined.empty()) << r.declined;
  // Millimetres off, a top may round down one step further, never up.
  int same = 0;
  for (double x = 0.25; x < 12; x += 0.5)
    for (double y = 0.25; y < 8; y += 0.5) {
      const double exact = top_at(closed, {x, y}, 0), got = top_at(r, {x, y}, 0);
      EXPECT_LE(got, exact) << x << ", " << y;
      EXPECT_GE(got, exact - 1) << x << ", " << y;
      same += got == exact ? 1 : 0;
    }
  EXPECT_GT(same, 300) << "of 384";
  // Roofs and walls 5 cm apart do not meet: that stays open.
  Solid apart = eaves;
  for (std::size_t k = apart.size() - 2; k < apart.size(); ++k)
    for (Vec3& v : apart[k].rings[0]) v.z += 0.05;
  EXPECT_EQ(shrink_solid(apart, 0, 1, 1).declined, "its faces close no volume");
}

/// Whether p lies in a roofed building: over its footprint (the reader's ground outline of its
/// parts, inside the walls), and the first face straight above p faces up (a roof or a
/// dormer's roof seen from inside, not a roof seen from above or an eave from below).
bool under_a_roof(const CityObject& object, Vec3 p) {
  if (std::none_of(object.footprint.begin(), object.footprint.end(), [&](const Polygon& f) {
        return inside(f, Vec2{p.x, p.y});
      }))
    return false;
  double nearest = std::numeric_limits<double>::infinity();
  bool up = false;
  for (const Surface3& f : object.surfaces) {
    const std::vector<Vec3>& r = f.rings.front();
    Vec3 n{0, 0, 0};  // Newell's normal
    for (std::size_t k = 0; k < r.size(); ++k) n += glm::cross(r[k], r[(k + 1) % r.size()]);
    if (std::abs(n.z) < 1e-9 * glm::length(n)) continue;  // a wall: no vertical line crosses it
    const double z = r[0].z - (n.x * (p.x - r[0].x) + n.y * (p.y - r[0].y)) / n.z;
    if (!(z > p.z) || z >= nearest) continue;
    Ring plan;
    for (const Vec3& v : r) plan.push_back({v.x, v.y});
    if (!inside_ring(plan, {p.x, p.y})) continue;
    nearest = z;
    up = n.z > 0;
  }
  return up;
}

TEST_F(SolidOccluders, ZurichsRoofsThatOverhangTheirWallsClose) {
  REQUIRE_SHARED_CITY(path, "zurich_subset_lod2.city.json");
  const City city = read_city({path});
  std::size_t shrunk = 0, occluding = 0;
  for (const CityObject& object : city.objects) {
    if (!object.occludes) continue;
    ++occluding;
    const ShrunkSolid s = shrink_solid(object.surfaces, object.ground_z, 1, 1);
    if (s.occluders.empty()) continue;
    ++shrunk;
    // Ray parity does not read these buildings: eaves are sheets without an underside, and
    // dormers stand as parts of their own on a roof face that runs on under them. So the test
    // reads them as a roofed building: inside its footprint, over its ground, under a roof.
    SCOPED_TRACE(object.source_id);
    expect_conservative_by([&](const Vec3& q) { return under_a_roof(object, q); }, s,
                           object.ground_z, 1, 30);
  }
  EXPECT_EQ(occluding, 49u);
  // 3 of 49 before the cuts; 39 with them (the rest: 5 narrower than 2ε once shrunk, 4 still
  // open, 1 with faces that cross; 2026-12-07).
  EXPECT_GE(shrunk, 39u);
}

TEST_F(SolidOccluders, ASolidAboveItsGroundHoldsNothingUp) {
  // A box from 5 to 10 m over ground at 0: the air under it is outside, all the way down.
  const ShrunkSolid s = shrink_solid(box(0, 0, 20, 12, 5, 10), 0, 1, 1);
  EXPECT_TRUE(s.occluders.empty());
  EXPECT_EQ(s.declined, "no column stands in the solid at least ε from its outside");
}

TEST_F(SolidOccluders, SurfacesWithAGapGiveNothing) {
  Solid solid = box(0, 0, 20, 12, 0, 10);
  solid.erase(face_where(solid, [](const Vec3& v) { return v.x == 20; }));  // a wall missing
  const ShrunkSolid s = shrink_solid(solid, 0, 1, 1);
  EXPECT_TRUE(s.occluders.empty());
  EXPECT_EQ(s.declined, "its faces close no volume");
  // The front wall in two halves with a slit of 1 mm between them: the outside reaches in.
  Solid slit = box(0, 0, 20, 12, 0, 10);
  slit.erase(face_where(slit, [](const Vec3& v) { return v.y == 0; }));
  slit.push_back({{{{0, 0, 0}, {10, 0, 0}, {10, 0, 10}, {0, 0, 10}}}});
  slit.push_back({{{{10.001, 0, 0}, {20, 0, 0}, {20, 0, 10}, {10.001, 0, 10}}}});
  EXPECT_TRUE(shrink_solid(slit, 0, 1, 1).occluders.empty());
}

TEST_F(SolidOccluders, SurfacesThatCannotBeASolidAreDeclined) {
  Solid solid = box(0, 0, 20, 12, 0, 10);
  solid[0].blocks = false;
  EXPECT_EQ(shrink_solid(solid, 0, 1, 1).declined,
            "a surface bounds where the building may be, not where it is");
  // A wall with a window hole that no face fills: open.
  Solid window = box(0, 0, 20, 12, 0, 10);
  window[0].rings.push_back({{5, 0, 2}, {5, 0, 4}, {7, 0, 4}, {7, 0, 2}});
  EXPECT_EQ(shrink_solid(window, 0, 1, 1).declined, "its faces close no volume");
  // Two boxes through each other: their faces intersect (TetGen 1.5 crashes on such a PLC, so
  // its -d pass finds them first).
  Solid crossing = box(0, 0, 10, 10, 0, 10);
  for (Surface3& f : box(5, 5, 15, 15, 5, 15)) crossing.push_back(f);
  const ShrunkSolid s = shrink_solid(crossing, 0, 1, 1);
  EXPECT_TRUE(s.occluders.empty());
  EXPECT_EQ(s.declined, "its faces intersect each other (TetGen -d)");
}

TEST_F(SolidOccluders, AGabledHouseAgreesWithThe25DRoute) {
  const Solid solid = gabled_house();
  const double epsilon = 1, step = 1;
  const ShrunkSolid s = shrink_solid(solid, 0, epsilon, step);
  ASSERT_TRUE(s.declined.empty()) << s.declined;
  expect_conservative(solid, s, 0, epsilon, 120);
  expect_conservative_at_edges(solid, s, 0, epsilon);
  // The exact 2.5D erosion of the roof (thesis 7.4) at y is 10 - |y - 4| - ε, inside the
  // footprint eroded by ε. The 3D route may lose a quarter of ε more (its squares) and a step.
  for (double x = 2; x <= 10; x += 0.7)
    for (double y = 1.6; y <= 6.4; y += 0.3) {
      const double exact = std::min(10 - std::abs(y - 4) - epsilon, 6.0);
      const double top = top_at(s, {x, y}, 0);
      EXPECT_LE(top, 10 - std::abs(y - 4) - epsilon + 1e-9) << x << ", " << y;
      EXPECT_GE(top, std::max(exact, 10 - std::abs(y - 4) - 1.25 * epsilon) - step - 1e-9)
          << x << ", " << y;
    }
  // The same house read from CityJSON and shrunk by the 2.5D route (stepped roof, blocks
  // eroded in 2D): the volume both keep differs by less than a fifth.
  std::string vertices, faces;
  std::vector<Vec3> points;
  for (const Surface3& f : solid) {
    faces += faces.empty() ? "[[" : ",[[";
    for (std::size_t k = 0; k < f.rings.front().size(); ++k) {
      const Vec3& v = f.rings.front()[k];
      auto it = std::find(points.begin(), points.end(), v);
      if (it == points.end()) {
        points.push_back(v);
        it = points.end() - 1;
      }
      faces += (k ? "," : "") + std::to_string(it - points.begin());
    }
    faces += "]]";
  }
  for (const Vec3& v : points)
    vertices += (vertices.empty() ? "[" : ",[") + std::to_string(static_cast<int>(v.x)) + "," +
                std::to_string(static_cast<int>(v.y)) + "," +
                std::to_string(static_cast<int>(v.z)) + "]";
  const std::string text = R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],)"
                           R"("translate":[0,0,0]},"CityObjects":{"house":{"type":"Building",)"
                           R"("geometry":[{"type":"Solid","lod":"2","boundaries":[[)" +
                           faces + "]]}]}},\"vertices\":[" + vertices + "]}";
  ReadOptions options;
  options.roof_step = step;
  const City city = read_city_text(text, "house.city.json", options);
  ASSERT_EQ(city.objects.size(), 1u);
  BlockOptions block_options;
  const std::vector<Occluder> flat =
      shrink_blocks(build_blocks(city.objects, block_options), epsilon);
  ASSERT_FALSE(flat.empty());
  // Volume of nested levels: each level's area times its height above the next lower one.
  auto volume = [](std::vector<Occluder> levels) {
    std::sort(levels.begin(), levels.end(),
              [](const Occluder& a, const Occluder& b) { return a.top_z < b.top_z; });
    double v = 0, below = 0;
    for (std::size_t k = 0; k < levels.size();) {
      const double h = levels[k].top_z;
      double a = 0;
      for (; k < levels.size() && levels[k].top_z == h; ++k) a += area(levels[k].shape);
      v += a * (h - below);
      below = h;
    }
    return v;
  };
  const double v3 = volume(s.occluders), v25 = volume(flat);
  EXPECT_NEAR(v3 / v25, 1.0, 0.2) << "3D " << v3 << " m3, 2.5D " << v25 << " m3";
}

TEST(SolidOccludersChoice, OnlyBuildingsThatAreNotHeightFieldsOverhang) {
  const Solid arcade = extruded_profile(
      {{0, 0}, {12, 0}, {12, 4}, {18, 4}, {18, 0}, {30, 0}, {30, 12}, {0, 12}}, 10);
  const Solid overhang =
      extruded_profile({{0, 0}, {10, 0}, {10, 4}, {14, 4}, {14, 10}, {7, 14}, {0, 10}}, 12);
  EXPECT_TRUE(overhangs(arcade, 0));
  EXPECT_TRUE(overhangs(overhang, 0));
  EXPECT_FALSE(overhangs(box(0, 0, 20, 12, 0, 10), 0));
  EXPECT_FALSE(overhangs(gabled_house(), 0));
  // A floor slab raised 20 cm (within the ground's tolerance) is still a floor.
  EXPECT_FALSE(overhangs(box(0, 0, 20, 12, 0.2, 10), 0));
}

TEST_F(SolidOccluders, AChildProcessGivesTheSameResultsInOrder) {
  const std::vector<Solid> solids = {
      box(0, 0, 20, 12, 0, 10), gabled_house(),
      extruded_profile({{0, 0}, {12, 0}, {12, 4}, {18, 4}, {18, 0}, {30, 0}, {30, 12}, {0, 12}},
                       10)};
  std::vector<SolidInput> inputs;
  for (const Solid& s : solids) inputs.push_back({&s, 0});
  const std::vector<ShrunkSolid> shrunk = shrink_solids(inputs, 1, 1, 60);
  ASSERT_EQ(shrunk.size(), solids.size());
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const ShrunkSolid here = shrink_solid(solids[k], 0, 1, 1);
    EXPECT_EQ(shrunk[k].declined, here.declined);
    EXPECT_EQ(shrunk[k].exterior_tetrahedra, here.exterior_tetrahedra);
    ASSERT_EQ(shrunk[k].occluders.size(), here.occluders.size()) << k;
    for (std::size_t j = 0; j < here.occluders.size(); ++j) {
      const Occluder &a = shrunk[k].occluders[j], &b = here.occluders[j];
      EXPECT_EQ(a.block, kSolidBlock);
      EXPECT_EQ(a.top_z, b.top_z);
      EXPECT_EQ(a.shape.outer, b.shape.outer);
      EXPECT_EQ(a.shape.holes, b.shape.holes);
      EXPECT_EQ(a.bounds.min, b.bounds.min);
      EXPECT_EQ(a.bounds.max, b.bounds.max);
    }
  }
}

TEST_F(SolidOccluders, AnExceptionInTheChildCostsThatBuildingOnly) {
  const Solid house = gabled_house(), bad = box(0, 0, 1, 1, 0, 1);
  const std::vector<ShrunkSolid> shrunk =
      shrink_solids({{&house, 0}, {&bad, 0}, {&house, 0}}, 60, [&](const SolidInput& in) {
        if (in.surfaces == &bad) throw std::runtime_error("boom");
        return shrink_solid(*in.surfaces, in.ground_z, 1, 1);
      });
  ASSERT_EQ(shrunk.size(), 3u);
  EXPECT_EQ(shrunk[0].declined, "");
  EXPECT_EQ(shrunk[1].declined, "the 3D route failed: boom");
  EXPECT_EQ(shrunk[2].declined, "");
  EXPECT_FALSE(shrunk[2].occluders.empty());
}

TEST_F(SolidOccluders, ABuildingThatRunsPastTheTimeLimitGivesNothing) {
  const Solid solid = gabled_house();
  const std::vector<ShrunkSolid> shrunk = shrink_solids({{&solid, 0}, {&solid, 0}}, 1, 1, 1e-9);
  ASSERT_EQ(shrunk.size(), 2u);
  for (const ShrunkSolid& s : shrunk) {
    EXPECT_EQ(s.declined, "the 3D route took longer than 0 s (TetGen 1.5 loops on some faces)");
    EXPECT_TRUE(s.occluders.empty());
  }
}

TEST_F(SolidOccluders, ACrashOrAnEndlessLoopCostsThatBuildingOnly) {
  // TetGen 1.5 crashed on a building of the 3D BAG tile (an assertion in its fillcavity) and
  // looped forever on others, before faces were triangulated here; such faces are stood in
  // for by a shrink that aborts on one building and spins on another.
  const Solid house = gabled_house(), crash = box(0, 0, 1, 1, 0, 1), spin = box(0, 0, 2, 2, 0, 2);
  const std::vector<SolidInput> inputs = {
      {&house, 0}, {&crash, 0}, {&house, 0}, {&spin, 0}, {&house, 0}};
  const std::vector<ShrunkSolid> shrunk = shrink_solids(inputs, 1, [&](const SolidInput& in) {
    if (in.surfaces == &crash) std::abort();
    if (in.surfaces == &spin)
      for (volatile bool forever = true; forever;) {
      }
    return shrink_solid(*in.surfaces, in.ground_z, 1, 1);
  });
  ASSERT_EQ(shrunk.size(), 5u);
  const ShrunkSolid here = shrink_solid(house, 0, 1, 1);
  for (std::size_t k : {0, 2, 4}) {
    EXPECT_EQ(shrunk[k].declined, "") << k;
    EXPECT_EQ(shrunk[k].occluders.size(), here.occluders.size()) << k;
  }
  EXPECT_EQ(shrunk[1].declined, "the 3D route crashed on its faces (TetGen 1.5 does on some)");
  EXPECT_EQ(shrunk[3].declined,
            "the 3D route took longer than 1 s (TetGen 1.5 loops on some faces)");
  EXPECT_TRUE(shrunk[1].occluders.empty());
  EXPECT_TRUE(shrunk[3].occluders.empty());
}

TEST(FaceTriangulation, AHoleIsLeftOutAndCrossingRingsAreRefused) {
  const std::vector<Vec3> p = {{0, 0, 10},  {20, 0, 10}, {20, 12, 10}, {0, 12, 10},
                               {8, 4, 10},  {8, 8, 10},  {12, 8, 10},  {12, 4, 10},
                               {18, 4, 10}, {25, 4, 10}, {25, 8, 10},  {18, 8, 10}};
  auto area_of = [&](const std::vector<std::array<int, 3>>& triangles) {
    double a = 0;
    for (const auto& t : triangles) {
      const Vec3 u = p[static_cast<std::size_t>(t[1])] - p[static_cast<std::size_t>(t[0])];
      const Vec3 v = p[static_cast<std::size_t>(t[2])] - p[static_cast<std::size_t>(t[0])];
      a += glm::length(glm::cross(u, v)) / 2;
    }
    return a;
  };
  std::vector<std::array<int, 3>> out;
  ASSERT_TRUE(triangulate_face(p, {{0, 1, 2, 3}, {4, 5, 6, 7}}, out));
  EXPECT_NEAR(area_of(out), 20 * 12 - 4 * 4, 1e-9);
  for (const auto& t : out)
    for (int v : t) EXPECT_LT(v, 8) << "a vertex that no ring has";
  std::vector<std::array<int, 3>> crossed;
  EXPECT_FALSE(triangulate_face(p, {{0, 1, 2, 3}, {8, 9, 10, 11}}, crossed));
  EXPECT_TRUE(crossed.empty());
  // A face standing on its edge in the x-y plane (a wall) is triangulated in its own plane.
  const std::vector<Vec3> wall = {{0, 0, 0}, {10, 0, 0}, {10, 0, 5}, {5, 0, 8}, {0, 0, 5}};
  std::vector<std::array<int, 3>> gable;
  ASSERT_TRUE(triangulate_face(wall, {{0, 1, 2, 3, 4}}, gable));
  EXPECT_EQ(gable.size(), 3u);
}

TEST(FaceTriangulation, ACutIsAnEdgeOfTheTrianglesAndKeepsTheHoleOut) {
  // The face with the hole of the test above, cut from the hole's corner (12, 4) to an inner
  // point (16, 2), as a wall's top edge ends inside a roof.
  std::vector<Vec3> p = {{0, 0, 10}, {20, 0, 10}, {20, 12, 10}, {0, 12, 10}, {8, 4, 10},
                         {8, 8, 10}, {12, 8, 10}, {12, 4, 10},  {16, 2, 10}, {20, 6, 10}};
  auto has_edge = [](const std::vector<std::array<int, 3>>& triangles, int a, int b) {
    return std::any_of(triangles.begin(), triangles.end(), [&](const std::array<int, 3>& t) {
      return std::count(t.begin(), t.end(), a) + std::count(t.begin(), t.end(), b) == 2;
    });
  };
  double area = 0;
  std::vector<std::array<int, 3>> out;
  ASSERT_TRUE(triangulate_face(p, {{0, 1, 2, 3}, {4, 5, 6, 7}}, {{7, 8}}, out));
  for (const auto& t : out) {
    const Vec3 u = p[static_cast<std::size_t>(t[1])] - p[static_cast<std::size_t>(t[0])];
    const Vec3 v = p[static_cast<std::size_t>(t[2])] - p[static_cast<std::size_t>(t[0])];
    area += glm::length(glm::cross(u, v)) / 2;
  }
  EXPECT_NEAR(area, 20 * 12 - 4 * 4, 1e-9) << "the cut divides the face, the hole stays out";
  EXPECT_TRUE(has_edge(out, 7, 8));
  // A cut that leaves the face, or crosses the hole, or ends on a ring's edge, is refused.
  std::vector<std::array<int, 3>> refused;
  p.push_back({25, 2, 10});
  EXPECT_FALSE(triangulate_face(p, {{0, 1, 2, 3}, {4, 5, 6, 7}}, {{8, 10}}, refused));
  EXPECT_FALSE(triangulate_face(p, {{0, 1, 2, 3}, {4, 5, 6, 7}}, {{8, 5}}, refused));
  EXPECT_FALSE(triangulate_face(p, {{0, 1, 2, 3}, {4, 5, 6, 7}}, {{8, 9}}, refused));
  EXPECT_TRUE(refused.empty());
}

}  // namespace
}  // namespace urbanpvs::geometry
