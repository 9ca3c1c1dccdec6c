// SPDX-License-Identifier: GPL-3.0-or-later
// OSM roof:shape as planar faces (RoofShapes.hpp): the faces tile the footprint and rise from
// the eaves to the top as the shape says, and through the GeoJSON reader the prisms under them
// never rise above them (thesis 7.1) while the faces become blocking surfaces for the validator.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/RoofShapes.hpp"

namespace urbanpvs::geometry {
namespace {

// The height of a planar face ring over p (fanned into triangles from its first vertex), or
// nothing when p lies outside it (within `tol` of it counts as inside).
std::optional<double> face_z(const std::vector<Vec3>& face, Vec2 p, double tol = 1e-9) {
  for (std::size_t i = 1; i + 1 < face.size(); ++i) {
    const Vec3 a = face[0], b = face[i], c = face[i + 1];
    const Vec2 ab{b.x - a.x, b.y - a.y}, ac{c.x - a.x, c.y - a.y}, ap{p.x - a.x, p.y - a.y};
    const double d = cross(ab, ac);
    if (std::abs(d) < 1e-12) continue;
    const double u = cross(ap, ac) / d, v = cross(ab, ap) / d;
    const double e = tol / std::sqrt(std::abs(d));
    if (u >= -e && v >= -e && u + v <= 1 + e) return a.z + u * (b.z - a.z) + v * (c.z - a.z);
  }
  return std::nullopt;
}

// The roof's height over p: the lowest of the faces over it (they agree on shared edges).
std::optional<double> roof_z(const std::vector<std::vector<Vec3>>& faces, Vec2 p) {
  std::optional<double> z;
  for (const auto& f : faces)
    if (auto fz = face_z(f, p, 1e-7)) z = z ? std::min(*z, *fz) : *fz;
  return z;
}

// A point inside the convex ring, from random barycentric weights of a fan triangle.
Vec2 point_in(const Ring& r, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> areas;
  double total = 0;
  for (std::size_t i = 1; i + 1 < r.size(); ++i)
    total += std::abs(cross(r[i] - r[0], r[i + 1] - r[0])), areas.push_back(total);
  const double pick = u(rng) * total;
  std::size_t i = 1;
  while (i + 1 < r.size() - 1 && areas[i - 1] < pick) ++i;
  double s = u(rng), t = u(rng);
  if (s + t > 1) s = 1 - s, t = 1 - t;
  return r[0] + s * (r[i] - r[0]) + t * (r[i + 1] - r[0]);
}

Ring rotated_rectangle(double length, double width, double angle, Vec2 at) {
  const Vec2 u{std::cos(angle), std::sin(angle)}, v{-u.y, u.x};
  return {at, at + length * u, at + length * u + width * v, at + width * v};
}

TEST(RoofShapes, GabledRidgeAlongTheLongerSidesOrAcross) {
  const Polygon house{{{0, 0}, {30, 0}, {30, 20}, {0, 20}}, {}};
  const auto along = shaped_roof(house, {"gabled", {}, RidgeOrientation::Along}, 8, 12);
  ASSERT_TRUE(along);
  EXPECT_EQ(along->faces.size(), 2u);
  EXPECT_EQ(along->walls.size(), 2u);  // the gables at x = 0 and x = 30
  EXPECT_NEAR(*roof_z(along->faces, {15, 10}), 12, 1e-9);
  EXPECT_NEAR(*roof_z(along->faces, {3, 10}), 12, 1e-9);
  EXPECT_NEAR(*roof_z(along->faces, {15, 0}), 8, 1e-9);
  EXPECT_NEAR(*roof_z(along->faces, {15, 15}), 10, 1e-9);
  for (const auto& wall : along->walls)
    for (const Vec3& v : wall) EXPECT_TRUE(v.x == 0 || v.x == 30);
  const auto across = shaped_roof(house, {"gabled", {}, RidgeOrientation::Across}, 8, 12);
  ASSERT_TRUE(across);
  EXPECT_NEAR(*roof_z(across->faces, {15, 0}), 12, 1e-9);
  EXPECT_NEAR(*roof_z(across->faces, {0, 10}), 8, 1e-9);
  EXPECT_NEAR(*roof_z(across->faces, {22.5, 10}), 10, 1e-9);
}

// Without roof:orientation the ridge may run either way, and a hipped roof's ridge may have any
// length: the model is the pyramid over the rectangle, the lower envelope of all of them.
TEST(RoofShapes, UntaggedRidgesAndHipsGiveTheLowerEnvelope) {
  const Polygon house{{{0, 0}, {30, 0}, {30, 20}, {0, 20}}, {}};
  const auto along = shaped_roof(house, {"gabled", {}, RidgeOrientation::Along}, 8, 12);
  const auto across = shaped_roof(house, {"gabled", {}, RidgeOrientation::Across}, 8, 12);
  ASSERT_TRUE(along && across);
  for (const char* s : {"gabled", "round", "gambrel", "hipped", "half-hipped", "mansard"}) {
    SCOPED_TRACE(s);
    const auto roof = shaped_roof(house, {s, {}, RidgeOrientation::Unknown}, 8, 12);
    ASSERT_TRUE(roof);
    EXPECT_EQ(roof->faces.size(), 4u);
    EXPECT_TRUE(roof->walls.empty());
    EXPECT_NEAR(*roof_z(roof->faces, {15, 10}), 12, 1e-9);  // the apex
    // Hipped roofs with the ridge along x, from none (the pyramid) to the whole length (the
    // gable): the model is at most the lowest of them.
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int k = 0; k < 500; ++k) {
      const Vec2 p{30 * u(rng), 20 * u(rng)};
      const double z = *roof_z(roof->faces, p);
      EXPECT_NEAR(z, std::min(*roof_z(along->faces, p), *roof_z(across->faces, p)), 1e-9);
      for (double ridge : {0.0, 5.0, 10.0, 20.0, 30.0}) {
        const double end = (30 - ridge) / 2;  // a hip's run
        const double side = 4 * std::min(p.y, 20 - p.y) / 10;
        const double hip = end > 0 ? 4 * std::min(p.x, 30 - p.x) / end : INFINITY;
        EXPECT_LE(z, 8 + std::min({side, hip, 4.0}) + 1e-9) << ridge;
      }
    }
  }
  const Polygon square{{{0, 0}, {20, 0}, {20, 20}, {0, 20}}, {}};
  const auto pyramid = shaped_roof(square, {"pyramidal", {}, RidgeOrientation::Unknown}, 8, 12);
  ASSERT_TRUE(pyramid);
  EXPECT_EQ(pyramid->faces.size(), 4u);
  EXPECT_NEAR(*roof_z(pyramid->faces, {10, 10}), 12, 1e-9);
  EXPECT_NEAR(*roof_z(pyramid->faces, {10, 5}), 10, 1e-9);
}

TEST(RoofShapes, SkillionFacesItsDirection) {
  const Polygon shed{{{0, 0}, {10, 0}, {10, 4}, {0, 4}}, {}};
  // Facing south (180°): high on the north side (y = 4), at the eaves on the south (y = 0).
  const auto south = shaped_roof(shed, {"skillion", 180.0, RidgeOrientation::Unknown}, 3, 5);
  ASSERT_TRUE(south);
  ASSERT_EQ(south->faces.size(), 1u);
  EXPECT_NEAR(*roof_z(south->faces, {5, 4}), 5, 1e-9);
  EXPECT_NEAR(*roof_z(south->faces, {5, 0}), 3, 1e-9);
  EXPECT_NEAR(*roof_z(south->faces, {5, 1}), 3.5, 1e-9);
  // Walls above the eaves: the north side (a quad) and the two ends (triangles); none south.
  EXPECT_EQ(south->walls.size(), 3u);
  // No direction: which side is high is unknown.
  EXPECT_FALSE(shaped_roof(shed, {"skillion", std::nullopt, RidgeOrientation::Unknown}, 3, 5));
}

TEST(RoofShapes, ShapesAndFootprintsNotModelledGiveNone) {
  const Polygon l_shape{{{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}, {}};
  for (const char* s : {"gabled", "hipped", "pyramidal"})
    EXPECT_FALSE(shaped_roof(l_shape, {s, {}, RidgeOrientation::Along}, 6, 9)) << s;
  const Polygon house{{{0, 0}, {30, 0}, {30, 20}, {0, 20}}, {}};
  for (const char* s : {"dome", "onion", "saltbox", "flat", "9.0", ""})
    EXPECT_FALSE(shaped_roof(house, {s, {}, RidgeOrientation::Along}, 6, 9)) << s;
  EXPECT_FALSE(shaped_roof(house, {"gabled", {}, RidgeOrientation::Along}, 9,
                           9));  // no height above the eaves
  // A parallelogram (60° corners) is no rectangle.
  const Polygon skew{{{0, 0}, {20, 0}, {25, 8.66}, {5, 8.66}}, {}};
  EXPECT_FALSE(shaped_roof(skew, {"gabled", {}, RidgeOrientation::Along}, 6, 9));
  // A point 5 cm outside a side is dropped: still a rectangle, within the footprint. One 5 cm
  // inside is kept: the rectangle over it would overhang the wall there.
  const Polygon bulge{{{0, 0}, {15, -0.05}, {30, 0}, {30, 20}, {0, 20}}, {}};
  EXPECT_TRUE(shaped_roof(bulge, {"gabled", {}, RidgeOrientation::Along}, 6, 9));
  const Polygon dent{{{0, 0}, {15, 0.05}, {30, 0}, {30, 20}, {0, 20}}, {}};
  EXPECT_FALSE(shaped_roof(dent, {"gabled", {}, RidgeOrientation::Along}, 6, 9));
  // Small dents that each pass, but add up to more than 2 cm inside the rectangle.
  const Polygon dents{{{0, 0}, {5, 0.018}, {10, 0.028}, {15, 0.018}, {20, 0}, {20, 10}, {0, 10}},
                      {}};
  EXPECT_FALSE(shaped_roof(dents, {"gabled", {}, RidgeOrientation::Along}, 6, 9));
}

// Random rotated rectangles and convex footprints: the faces cover every point of the
// footprint once (up to shared edges), between the eaves and the top, and reach the top.
TEST(RoofShapes, FacesTileTheFootprintBetweenEavesAndTop) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> len(4, 40), ang(0, 2 * M_PI), pos(-500, 500);
  for (int trial = 0; trial < 200; ++trial) {
    const double l = len(rng), w = len(rng), eaves = 3 + len(rng) / 4, top = eaves + len(rng) / 8;
    const Ring r = rotated_rectangle(l, w, ang(rng), {pos(rng), pos(rng)});
    for (const char* s : {"gabled", "hipped", "pyramidal"}) {
      for (RidgeOrientation ridge :
           {RidgeOrientation::Unknown, RidgeOrientation::Along, RidgeOrientation::Across}) {
        SCOPED_TRACE(std::string(s) + " trial " + std::to_string(trial));
        const auto roof = shaped_roof({r, {}}, {s, {}, ridge}, eaves, top);
        ASSERT_TRUE(roof);
        double highest = -INFINITY;
        for (int k = 0; k < 100; ++k) {
          const Vec2 p = point_in(r, rng);
          const std::optional<double> z = roof_z(roof->faces, p);
          ASSERT_TRUE(z) << p.x << " " << p.y;
          EXPECT_GE(*z, eaves - 1e-9);
          EXPECT_LE(*z, top + 1e-9);
          highest = std::max(highest, *z);
          // Faces overlap nowhere: at most one holds p away from their edges.
          int holding = 0;
          for (const auto& f : roof->faces) holding += face_z(f, p, -1e-6).has_value();
          EXPECT_LE(holding, 1);
        }
        EXPECT_GT(highest, eaves + 0.5 * (top - eaves));
        for (Vec2 corner : r) EXPECT_NEAR(*roof_z(roof->faces, corner), eaves, 1e-7);
        for (const auto& f : roof->faces)
          for (const Vec3& v : f) EXPECT_TRUE(std::abs(v.z - eaves) < 1e-12 || v.z == top);
      }
    }
  }
}

TEST(RoofShapes, DirectionsAsDegreesOrCompassPoints) {
  EXPECT_DOUBLE_EQ(*roof_direction("90"), 90);
  EXPECT_DOUBLE_EQ(*roof_direction("-90"), 270);
  EXPECT_DOUBLE_EQ(*roof_direction("450"), 90);
  EXPECT_DOUBLE_EQ(*roof_direction("SW"), 225);
  EXPECT_DOUBLE_EQ(*roof_direction("nne"), 22.5);
  EXPECT_DOUBLE_EQ(*roof_direction("N"), 0);
  EXPECT_FALSE(roof_direction("up"));
  EXPECT_FALSE(roof_direction(""));
  EXPECT_FALSE(roof_direction("90deg"));
}

// ---- through the GeoJSON reader ----

constexpr const char* kRoofs = R"({"type":"FeatureCollection","features":[
{"type":"Feature","id":"gable","properties":{"height":12,"roof:shape":"gabled","roof:height":4,"roof:orientation":"along"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[30,0],[30,20],[0,20],[0,0]]]}},
{"type":"Feature","id":"hip","properties":{"height":"13","roof:shape":"Hipped","roof:height":"3 m","building:levels":3},"geometry":{"type":"Polygon","coordinates":[[[40,0],[70,0],[70,20],[40,20],[40,0]]]}},
{"type":"Feature","id":"pyramid","properties":{"height":18,"roof:height":6,"roof:shape":"pyramidal"},"geometry":{"type":"Polygon","coordinates":[[[80,0],[100,0],[105,10],[100,20],[80,20],[80,0]]]}},
{"type":"Feature","id":"shed","properties":{"height":5,"roof:shape":"skillion","roof:height":2,"roof:direction":"S"},"geometry":{"type":"Polygon","coordinates":[[[0,40],[10,40],[10,44],[0,44],[0,40]]]}},
{"type":"Feature","id":"ell","properties":{"height":9,"roof:shape":"gabled","roof:height":3},"geometry":{"type":"Polygon","coordinates":[[[40,40],[60,40],[60,48],[48,48],[48,60],[40,60],[40,40]]]}},
{"type":"Feature","id":"dome","properties":{"height":20,"roof:shape":"dome","roof:height":5},"geometry":{"type":"Polygon","coordinates":[[[80,40],[100,40],[100,60],[80,60],[80,40]]]}},
{"type":"Feature","id":"storeys","properties":{"building:levels":4,"roof:levels":2,"roof:shape":"pyramidal"},"geometry":{"type":"Polygon","coordinates":[[[80,80],[100,80],[100,100],[80,100],[80,80]]]}},
{"type":"Feature","id":"guessed","properties":{"height":12,"roof:shape":"gabled","roof:levels":1,"roof:orientation":"along"},"geometry":{"type":"Polygon","coordinates":[[[0,80],[30,80],[30,90],[0,90],[0,80]]]}},
{"type":"Feature","id":"canopy","properties":{"building":"roof","height":5,"roof:shape":"gabled","roof:height":1,"roof:orientation":"along"},"geometry":{"type":"Polygon","coordinates":[[[40,80],[60,80],[60,90],[40,90],[40,80]]]}}
]})";

const CityObject& object(const City& c, const std::string& id) {
  for (const CityObject& o : c.objects)
    if (o.source_id == id) return o;
  throw std::runtime_error("no object " + id);
}

// The object's blocking faces that are neither vertical nor below `above`: its roof faces.
std::vector<std::vector<Vec3>> roof_faces_of(const CityObject& o, double above) {
  std::vector<std::vector<Vec3>> out;
  for (const Surface3& s : o.surfaces) {
    if (!s.blocks || s.rings.size() != 1) continue;
    const auto& r = s.rings[0];
    double lo = INFINITY, hi = -INFINITY, a = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      lo = std::min(lo, r[i].z), hi = std::max(hi, r[i].z);
      const Vec3 p = r[i], q = r[(i + 1) % r.size()];
      a += p.x * q.y - q.x * p.y;
    }
    if (hi > above + 1e-9 && std::abs(a) > 1e-9) out.push_back(r);
  }
  return out;
}

TEST(RoofShapesRead, PrismsUnderTheFacesNeverRiseAboveThem) {
  ReadOptions options;
  options.coordinates = ReadOptions::Coordinates::Projected;
  const City c = read_city_text(kRoofs, "roofs.geojson", options);
  EXPECT_EQ(c.report.roof_shapes, 4u);
  struct Expected {
    const char* id;
    double eaves, top;
  };
  std::mt19937 rng(3);
  for (const Expected& e : {Expected{"gable", 8, 12}, Expected{"hip", 10, 13},
                            Expected{"pyramid", 12, 18}, Expected{"shed", 3, 5}}) {
    SCOPED_TRACE(e.id);
    const CityObject& o = object(c, e.id);
    ASSERT_EQ(o.occluders.size(), 1u);
    EXPECT_NEAR(o.occluders[0].top_z, e.eaves, 1e-9);
    ASSERT_FALSE(o.roof_prisms.empty());
    const std::vector<std::vector<Vec3>> faces = roof_faces_of(o, e.eaves);
    ASSERT_FALSE(faces.empty());
    double reached = -INFINITY;
    for (const RoofPrism& prism : o.roof_prisms) {
      EXPECT_EQ(prism.ground_z, 0.0);
      const Ring& r = prism.footprint.outer;
      for (int k = 0; k < 300; ++k) {
        // Points of the prism's plan: fan triangles of its (possibly non-convex) outer ring
        // that lie inside it.
        const Vec2 p = point_in(r, rng);
        if (!inside(prism.footprint, p)) continue;
        const std::optional<double> z = roof_z(faces, p);
        ASSERT_TRUE(z) << p.x << " " << p.y;
        EXPECT_LE(prism.top_at(p), *z + 1e-9);
        reached = std::max(reached, prism.top_at(p));
      }
    }
    // The prisms are worth having: they reach well above the eaves.
    EXPECT_GT(reached, e.eaves + 0.5 * (e.top - e.eaves));
  }
  // Shapes or footprints not modelled, eaves from guessed storey heights (roof:levels, or
  // building:levels with roof:levels above them): no faces, the roof space open.
  for (const char* id : {"ell", "dome", "guessed", "storeys"}) {
    const CityObject& o = object(c, id);
    EXPECT_TRUE(o.roof_prisms.empty()) << id;
    EXPECT_TRUE(roof_faces_of(o, o.occluders.at(0).top_z).empty()) << id;
  }
  EXPECT_DOUBLE_EQ(object(c, "guessed").occluders.at(0).top_z, 9.0);
  EXPECT_DOUBLE_EQ(object(c, "storeys").occluders.at(0).top_z, 12.0);
  // A roof on open sides: no occluder, and nothing of it blocks a sight line.
  const CityObject& canopy = object(c, "canopy");
  EXPECT_TRUE(canopy.occluders.empty());
  EXPECT_TRUE(canopy.roof_prisms.empty());
  for (const Surface3& s : canopy.surfaces) EXPECT_FALSE(s.blocks);
  EXPECT_FALSE(canopy.surfaces.empty());
  EXPECT_DOUBLE_EQ(canopy.bbox.zmax, 5.0);
  EXPECT_EQ(c.report.open_roofs, 1u);
}

TEST(RoofShapesRead, SurfacesAboveTheEavesBlockOnlyWhereTheShapeIsKnown) {
  ReadOptions options;
  options.coordinates = ReadOptions::Coordinates::Projected;
  for (bool sloped : {true, false}) {
    options.sloped_roofs = sloped;
    const City c = read_city_text(kRoofs, "roofs.geojson", options);
    // The gable: two roof faces and two gable walls block above the eaves with the shape.
    std::size_t gable_blocking = 0, open_above = 0;
    for (const Surface3& s : object(c, "gable").surfaces) {
      double hi = -INFINITY;
      for (const auto& r : s.rings)
        for (const Vec3& v : r) hi = std::max(hi, v.z);
      if (hi > 8 + 1e-9) (s.blocks ? gable_blocking : open_above) += 1;
    }
    EXPECT_EQ(gable_blocking, sloped ? 4u : 0u);
    EXPECT_EQ(open_above, 5u);  // the prism over the eaves: where the roof may be, a target
    EXPECT_EQ(object(c, "gable").roof_prisms.empty(), !sloped);
    // A roof above its walls: the space over the eaves blocks nowhere but at the shape's faces
    // (four on the hipped roof, five on the pentagon's pyramid). The storeys' walls come from
    // building:levels and their roof from roof:levels above them: never a solid prism to the top.
    for (auto [id, eaves, faces] : {std::tuple{"hip", 10.0, 4u}, std::tuple{"pyramid", 12.0, 5u},
                                    std::tuple{"storeys", 12.0, 0u}}) {
      std::size_t blocking_above = 0;
      for (const Surface3& s : object(c, id).surfaces) {
        double hi = -INFINITY;
        for (const auto& r : s.rings)
          for (const Vec3& v : r) hi = std::max(hi, v.z);
        if (hi > eaves + 1e-9 && s.blocks) ++blocking_above;
      }
      EXPECT_EQ(blocking_above, sloped ? faces : 0u) << id;
    }
  }
}

}  // namespace
}  // namespace urbanpvs::geometry
