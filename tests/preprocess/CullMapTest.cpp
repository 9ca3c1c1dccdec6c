// SPDX-License-Identifier: GPL-3.0-or-later
// Cull maps (thesis 4.2-4.3, 5.5) against a brute-force reference that shares no code with the
// rasterizer: for every pixel centre, every facing edge is tested directly (point in the wedge
// behind the edge, height of the sight plane), then max over edges and min over samples.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "urbanpvs/geometry/city/ObjectOutline.hpp"
#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"
#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"

namespace urbanpvs::preprocess {
namespace {

using geometry::Occluder;
using geometry::Polygon;

struct Reference {
  double height = -std::numeric_limits<double>::infinity();
  double boundary_distance = std::numeric_limits<double>::infinity();  // to any wedge side
};

double line_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  return std::abs(geometry::cross(d, p - a)) / std::hypot(d.x, d.y);
}

// Height of the umbra of one sample at p, by definition (thesis 4.2.1).
Reference reference_height(const Vec3& v3, const std::vector<Occluder>& occluders, Vec2 p) {
  Reference r;
  const Vec2 v{v3.x, v3.y};
  for (const Occluder& o : occluders)
    geometry::for_each_edge(o.shape, [&](Vec2 a, Vec2 b) {
      // A wall casts a shadow when it faces V, and every wall when V is above its top (a line
      // from above comes down through the top and out through a wall facing away).
      const double side_v = geometry::cross(b - a, v - a);
      if (side_v == 0 || (side_v > 0 && !(v3.z > o.top_z))) return;
      r.boundary_distance = std::min({r.boundary_distance, line_distance(p, a, b),
                                      line_distance(p, v, a), line_distance(p, v, b)});
      const double side_p = geometry::cross(b - a, p - a);
      const bool behind = side_v < 0 ? side_p > 0 : side_p < 0;  // across the edge from V
      const bool within = geometry::cross(a - v, p - v) * geometry::cross(a - v, b - v) >= 0 &&
                          geometry::cross(b - v, p - v) * geometry::cross(b - v, a - v) >= 0;
      if (!behind || !within) return;
      // The sight line from V over the edge's top, continued to p (similar triangles).
      const double t =
          geometry::cross(a - v, b - a) / geometry::cross(p - v, b - a);  // q = v + t(p - v)
      const double h = v3.z + (o.top_z - v3.z) / t;
      r.height = std::max(r.height, h);
    });
  return r;
}

std::vector<Occluder> random_occluders(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> pos(5, 195), size(3, 25), height(4, 40);
  std::vector<Occluder> out;
  for (int i = 0; i < n; ++i) {
    const double x = pos(rng), y = pos(rng), w = size(rng), h = size(rng);
    Occluder o;
    o.top_z = height(rng);
    o.shape = Polygon{{{x, y}, {x + w, y}, {x + w * 0.8, y + h}, {x - w * 0.1, y + h * 0.9}}, {}};
    o.bounds = geometry::bounds(o.shape);
    out.push_back(std::move(o));
  }
  return out;
}

bool inside_any(const std::vector<Occluder>& occ, Vec2 p) {
  for (const Occluder& o : occ)
    if (geometry::inside(o.shape, p)) return true;
  return false;
}

TEST(CullMap, CpuRasterizerMatchesBruteForce) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> pos(0, 200), eye(0.5, 30);
  std::size_t compared = 0, near_boundary = 0;
  for (int scene = 0; scene < 60; ++scene) {
    const std::vector<Occluder> occ = random_occluders(rng, 1 + scene % 12);
    Vec3 v{pos(rng), pos(rng), eye(rng)};
    while (inside_any(occ, {v.x, v.y})) v = {pos(rng), pos(rng), eye(rng)};
    const CullMapGrid grid = CullMapGrid::covering({{-10, -10}, {210, 210}}, 1.3);
    CullMap map(grid);
    render_sample(v, pointers_to(occ), map);
    for (int j = 0; j < grid.height; ++j)
      for (int i = 0; i < grid.width; ++i) {
        const Reference r = reference_height(v, occ, grid.center(i, j));
        const float expected =
            std::isinf(r.height) ? CullMap::kNothingHidden : float_below(r.height);
        if (r.boundary_distance < 1e-6) {
          ++near_boundary;  // a centre on a wedge side may go either way
          continue;
        }
        ++compared;
        // The two compute the same plane differently; allow a few float steps.
        if (std::isinf(expected)) {
          ASSERT_EQ(map.at(i, j), expected) << "scene " << scene << " pixel " << i << "," << j;
        } else {
          ASSERT_NEAR(map.at(i, j), expected, 1e-5 * (1 + std::abs(expected)))
              << "scene " << scene << " pixel " << i << "," << j;
        }
      }
  }
  EXPECT_GT(compared, 100000u);
  EXPECT_LT(near_boundary, compared / 1000);
}

TEST(CullMap, CellMapIsMinOverSamplesOfMaxOverOccluders) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(0, 200), eye(0.5, 3);
  for (int scene = 0; scene < 15; ++scene) {
    const std::vector<Occluder> occ = random_occluders(rng, 8);
    std::vector<Vec3> samples;
    while (samples.size() < 6) {
      const Vec3 v{pos(rng), pos(rng), eye(rng)};
      if (!inside_any(occ, {v.x, v.y})) samples.push_back(v);
    }
    const CullMapGrid grid = CullMapGrid::covering({{0, 0}, {200, 200}}, 1.0);
    const CullMap cell = cell_cull_map(grid, samples, occ);
    for (int j = 0; j < grid.height; j += 3)
      for (int i = 0; i < grid.width; i += 3) {
        double lowest = std::numeric_limits<double>::infinity();
        bool ambiguous = false;
        for (const Vec3& s : samples) {
          const Reference r = reference_height(s, occ, grid.center(i, j));
          ambiguous |= r.boundary_distance < 1e-6;
          lowest = std::min(lowest, r.height);
        }
        if (ambiguous) continue;
        if (std::isinf(lowest)) {
          ASSERT_EQ(cell.at(i, j), CullMap::kNothingHidden);
        } else {
          ASSERT_NEAR(cell.at(i, j), float_below(lowest), 1e-5 * (1 + std::abs(lowest)));
        }
      }
  }
}

// Samples on the three top edges of a triangular cell, at most 2ε apart (thesis 5.3).
std::vector<Vec3> cell_samples(Vec2 a, Vec2 b, Vec2 c, double z, double eps) {
  std::vector<Vec3> s;
  for (auto [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    const int n = std::max(1, static_cast<int>(std::ceil(len / (2 * eps))));
    for (int k = 0; k < n; ++k) {
      const Vec2 x = p + (double(k) / n) * (q - p);
      s.push_back({x.x, x.y, z});
    }
  }
  return s;
}

geometry::CityObject box_object(std::uint32_t index, double x0, double y0, double x1, double y1,
                                double top) {
  geometry::CityObject o;
  o.index = index;
  o.bbox.extend(Vec2{x0, y0}, 0);
  o.bbox.extend(Vec2{x1, y1}, top);
  return o;
}

/// The outline of every object, as the bake tests them.
std::vector<geometry::Ring> outlines(const std::vector<geometry::CityObject>& objects) {
  std::vector<geometry::Ring> out;
  for (const geometry::CityObject& o : objects) out.push_back(geometry::object_outline(o));
  return out;
}

/// A building of `w` × `d` m and height `top`, centred at (cx, cy), turned by `angle`: its
/// roof and its footprint as the readers give them, its box around both.
geometry::CityObject turned_object(std::uint32_t index, double cx, double cy, double w, double d,
                                   double angle, double top) {
  geometry::CityObject o;
  o.index = index;
  geometry::Ring ring;
  for (const auto& [u, v] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}) {
    const double x = u * w, y = v * d;
    ring.push_back({cx + x * std::cos(angle) - y * std::sin(angle),
                    cy + x * std::sin(angle) + y * std::cos(angle)});
  }
  geometry::Surface3 roof;
  roof.rings.emplace_back();
  for (const Vec2& p : ring) {
    roof.rings.back().push_back({p.x, p.y, top});
    o.bbox.extend(p, 0);
    o.bbox.extend(p, top);
  }
  o.surfaces.push_back(roof);
  o.footprint.push_back({ring, {}});
  return o;
}

/// Whether the closed square of pixel (i, j) of `g` grown by `margin` meets the convex `ring`:
/// no separating axis among the two coordinate axes and the ring's edge normals.
bool pixel_meets(const CullMapGrid& g, int i, int j, const geometry::Ring& ring, double margin) {
  const Vec2 lo{g.origin.x + i * g.pixel - margin, g.origin.y + j * g.pixel - margin};
  const Vec2 hi{lo.x + g.pixel + 2 * margin, lo.y + g.pixel + 2 * margin};
  const std::array<Vec2, 4> square{lo, Vec2{hi.x, lo.y}, hi, Vec2{lo.x, hi.y}};
  std::vector<Vec2> axes{{1, 0}, {0, 1}};
  for (std::size_t e = 0; e < ring.size(); ++e) {
    const Vec2 d = ring[(e + 1) % ring.size()] - ring[e];
    axes.push_back({-d.y, d.x});
  }
  for (const Vec2& a : axes) {
    double p0 = 1e300, p1 = -1e300, q0 = 1e300, q1 = -1e300;
    for (const Vec2& p : ring) p0 = std::min(p0, glm::dot(a, p)), p1 = std::max(p1, glm::dot(a, p));
    for (const Vec2& q : square)
      q0 = std::min(q0, glm::dot(a, q)), q1 = std::max(q1, glm::dot(a, q));
    if (p1 < q0 || q1 < p0) return false;
  }
  return true;
}

Occluder wall(double x0, double y0, double x1, double y1, double top) {
  Occluder o;
  o.top_z = top;
  o.shape = Polygon{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}};
  o.bounds = geometry::bounds(o.shape);
  return o;
}

// A cell south of a wall: a low building behind the wall is hidden, a tall one is seen over it,
// one off to the side is seen past its end. Two walls with a gap hide a building only together
// (penumbra fusion, thesis figure 5.2c): each wall alone leaves it visible from some sample.
TEST(CullMap, HandBuiltScene) {
  const double eps = 1.0;
  const std::vector<Vec3> samples = cell_samples({40, 0}, {60, 0}, {50, 10}, 2.0, eps);
  const CullMapGrid grid = CullMapGrid::covering({{-100, -50}, {200, 250}}, 1.0);
  std::vector<Occluder> occ{wall(0, 20, 100, 30, 15)};
  const std::vector<geometry::CityObject> objects{
      box_object(0, 40, 40, 60, 60, 12),    // low, right behind the wall
      box_object(1, 40, 40, 60, 60, 80),    // tall: seen over the wall
      box_object(2, 140, 40, 160, 60, 12),  // beyond the wall's end
  };
  const CullMap map = cell_cull_map(grid, samples, occ);
  EXPECT_EQ(visible_objects(map, objects, outlines(objects)), (std::vector<std::uint32_t>{1, 2}));

  // Fusion: two staggered walls whose union blocks the view to a building far behind, though
  // neither does alone.
  const std::vector<Occluder> left{wall(-20, 30, 52, 33, 20)};
  const std::vector<Occluder> right{wall(48, 36, 120, 39, 20)};
  std::vector<Occluder> both = left;
  both.push_back(right[0]);
  const std::vector<geometry::CityObject> far{box_object(0, 45, 120, 55, 130, 10)};
  EXPECT_EQ(visible_objects(cell_cull_map(grid, samples, left), far, outlines(far)).size(), 1u);
  EXPECT_EQ(visible_objects(cell_cull_map(grid, samples, right), far, outlines(far)).size(), 1u);
  EXPECT_TRUE(visible_objects(cell_cull_map(grid, samples, both), far, outlines(far)).empty());
}

TEST(CullMap, ObjectsReachingOutsideTheMapAreVisible) {
  CullMap map(CullMapGrid::covering({{0, 0}, {10, 10}}, 1.0));
  map.fill(100.0f);
  geometry::Box3 inside_box, crossing;
  inside_box.extend(Vec2{2, 2}, 0), inside_box.extend(Vec2{3, 3}, 5);
  crossing.extend(Vec2{8, 8}, 0), crossing.extend(Vec2{12, 9}, 5);
  EXPECT_TRUE(hidden_by(map, inside_box));
  EXPECT_FALSE(hidden_by(map, crossing));
  map.at(3, 3) = 4.0f;  // the box's corner (3, 3) touches pixel (3, 3): any touch counts
  EXPECT_FALSE(hidden_by(map, inside_box));
}

// The outline covers the object: every point of its geometry; without points, a box beyond
// them, or when it occludes nothing, the outline is the box.
TEST(ObjectOutline, ContainsTheObjectAndFallsBackToTheBox) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0, 3.14159), size(3, 40);
  for (int trial = 0; trial < 200; ++trial) {
    const geometry::CityObject o = turned_object(0, 100, 200, size(rng), size(rng), angle(rng), 9);
    const geometry::Ring hull = geometry::object_outline(o);
    ASSERT_GE(hull.size(), 3u);
    for (std::size_t e = 0; e < hull.size(); ++e) {
      const Vec2 a = hull[e], b = hull[(e + 1) % hull.size()];
      for (const Vec3& p : o.surfaces[0].rings[0]) {  // left of every edge: inside, CCW
        EXPECT_GE((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x), -1e-9);
      }
    }
  }
  geometry::CityObject o = turned_object(0, 0, 0, 20, 10, 0.5, 9);
  o.occludes = false;
  EXPECT_EQ(geometry::object_outline(o).size(), 4u);
  EXPECT_EQ(geometry::object_outline(o)[0], o.bbox.xy.min);
  o.occludes = true;
  o.bbox.extend(Vec2{30, 0}, 0);  // geometry the surfaces do not hold
  EXPECT_EQ(geometry::object_outline(o)[0], o.bbox.xy.min);
  EXPECT_EQ(geometry::object_outline(box_object(0, 1, 2, 3, 4, 5))[2], (Vec2{3, 4}));
}

// The pixels the outline test reads are exactly those whose square meets the outline (up to a
// micrometre at a border): every one it must read (a point of the object may lie there), and
// none the object cannot reach. Found one pixel at a time: the map is high everywhere but at
// that pixel.
TEST(CullMap, OutlineTestReadsExactlyThePixelsTheOutlineTouches) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> angle(0, 3.14159), size(0.5, 12), at(20, 30);
  const CullMapGrid grid = CullMapGrid::covering({{0, 0}, {50, 50}}, 1.0);
  CullMap map(grid);
  int fewer = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const geometry::CityObject o =
        turned_object(0, at(rng), at(rng), size(rng), size(rng), angle(rng), 10);
    const geometry::Ring hull = geometry::object_outline(o);
    const auto [i0, j0, i1, j1] = grid.touched(o.bbox.xy);
    long long read = 0;
    for (long long j = j0; j <= j1; ++j) {
      for (long long i = i0; i <= i1; ++i) {
        map.fill(100.0f);
        map.at(static_cast<int>(i), static_cast<int>(j)) = 5.0f;
        const bool tested = !hidden_by(map, o.bbox, hull);
        read += tested;
        const int pi = static_cast<int>(i), pj = static_cast<int>(j);
        if (pixel_meets(grid, pi, pj, hull, -1e-6)) {
          EXPECT_TRUE(tested) << "trial " << trial << " pixel " << i << "," << j;
        }
        if (!pixel_meets(grid, pi, pj, hull, 1e-6)) {
          EXPECT_FALSE(tested) << "trial " << trial << " pixel " << i << "," << j;
        }
      }
    }
    fewer += read < (i1 - i0 + 1) * (j1 - j0 + 1);
  }
  EXPECT_GT(fewer, 100);  // turned buildings cover fewer pixels than their boxes
}

// A turned building behind a turned wall: the wall's shadow covers the building but not the
// corners of its box, which reach into the open street.
TEST(CullMap, ATurnedBuildingIsHiddenByItsOutlineNotByItsBox) {
  const std::vector<Vec3> samples = cell_samples({0, -30}, {10, -30}, {5, -20}, 2.0, 1.0);
  const CullMapGrid grid = CullMapGrid::covering({{-100, -100}, {100, 100}}, 1.0);
  Occluder w;
  w.top_z = 30;
  geometry::Ring slab;  // 40 m x 4 m, turned by 45 degrees
  for (const auto& [u, v] : {std::pair{-20.0, -2.0}, {20.0, -2.0}, {20.0, 2.0}, {-20.0, 2.0}}) {
    slab.push_back({5 + (u - v) * std::sqrt(0.5), (u + v) * std::sqrt(0.5)});
  }
  w.shape = Polygon{slab, {}};
  w.bounds = geometry::bounds(w.shape);
  const CullMap map = cell_cull_map(grid, samples, std::vector<Occluder>{w});
  const geometry::CityObject o = turned_object(0, 12, 12, 24, 3, 0.7854, 8);
  EXPECT_TRUE(hidden_by(map, o.bbox, geometry::object_outline(o)));
  EXPECT_FALSE(hidden_by(map, o.bbox));
}

TEST(CullMapSettings, RefusesPixelsTooLargeForEpsilon) {
  CullMapSettings ok{1.0, 1.39};
  EXPECT_NO_THROW(ok.validate());
  CullMapSettings bad{1.0, 2.0};
  try {
    bad.validate();
    FAIL() << "accepted pixel 2 m with epsilon 1 m";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lower the pixel size to <= 1.399"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace urbanpvs::preprocess
