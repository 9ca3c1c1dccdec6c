// SPDX-License-Identifier: GPL-3.0-or-later
// Cull maps (thesis 4.2-4.3, 5.5) against a brute-force reference that shares no code with the
// rasterizer: for every pixel centre, every facing edge is tested directly (point in the wedge
// behind the edge, height of the sight plane), then max over edges and min over samples.
#include <gtest/gtest.h>

#include <random>

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
      const double side_v = geometry::cross(b - a, v - a);
      if (side_v >= 0) return;  // back-facing
      r.boundary_distance = std::min({r.boundary_distance, line_distance(p, a, b),
                                      line_distance(p, v, a), line_distance(p, v, b)});
      const bool behind = geometry::cross(b - a, p - a) > 0;
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
  EXPECT_EQ(visible_objects(map, objects), (std::vector<std::uint32_t>{1, 2}));

  // Fusion: two staggered walls whose union blocks the view to a building far behind, though
  // neither does alone.
  const std::vector<Occluder> left{wall(-20, 30, 52, 33, 20)};
  const std::vector<Occluder> right{wall(48, 36, 120, 39, 20)};
  std::vector<Occluder> both = left;
  both.push_back(right[0]);
  const std::vector<geometry::CityObject> far{box_object(0, 45, 120, 55, 130, 10)};
  EXPECT_EQ(visible_objects(cell_cull_map(grid, samples, left), far).size(), 1u);
  EXPECT_EQ(visible_objects(cell_cull_map(grid, samples, right), far).size(), 1u);
  EXPECT_TRUE(visible_objects(cell_cull_map(grid, samples, both), far).empty());
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
