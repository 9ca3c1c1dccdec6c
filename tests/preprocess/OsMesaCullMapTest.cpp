// SPDX-License-Identifier: GPL-3.0-or-later
// The OSMesa backend against the CPU reference on random scenes (every other occluder with a
// sloped top): both sample shadows at pixel
// centres, so they must agree up to the depth precision, and the OpenGL map must never be
// higher than the exact one (conservative read-back).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"
#include "urbanpvs/preprocess/visibility/OsMesaCullMapRenderer.hpp"

namespace urbanpvs::preprocess {
namespace {

using geometry::Occluder;

std::vector<Occluder> random_occluders(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> pos(5, 295), size(3, 30), height(4, 50);
  std::vector<Occluder> out;
  for (int i = 0; i < n; ++i) {
    const double x = pos(rng), y = pos(rng), w = size(rng), h = size(rng);
    Occluder o;
    o.top_z = height(rng);
    o.shape = geometry::Polygon{
        {{x, y}, {x + w, y + 0.3 * h}, {x + 0.7 * w, y + h}, {x - 0.2 * w, y + 0.8 * h}}, {}};
    o.bounds = geometry::bounds(o.shape);
    if (i % 2 == 1) {  // a sloped top (thesis 4.2.1), everywhere above the ground
      std::uniform_real_distribution<double> slope(-0.3, 0.3);
      o.origin = {x, y};
      o.slope = {slope(rng), slope(rng)};
      o.top_z += std::max(0.0, 1.0 - o.top_low());
    }
    out.push_back(std::move(o));
  }
  return out;
}

TEST(OsMesaCullMap, AgreesWithCpuReference) {
  OsMesaCullMapRenderer gl;
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> pos(0, 300), eye(0.5, 3);
  const double zlo = -10, zhi = 200;
  const double tol = OsMesaCullMapRenderer::kDepthMargin * 2 * (zhi - zlo);
  std::size_t pixels = 0, border_pixels = 0;
  for (int scene = 0; scene < 120; ++scene) {
    const std::vector<Occluder> occ = random_occluders(rng, 2 + scene % 15);
    std::vector<Vec3> samples;
    while (samples.size() < 1 + static_cast<std::size_t>(scene % 7)) {
      const Vec3 v{pos(rng), pos(rng), eye(rng)};
      bool inside = false;
      for (const Occluder& o : occ) inside |= geometry::inside(o.shape, {v.x, v.y});
      if (!inside) samples.push_back(v);
    }
    const CullMapGrid grid = CullMapGrid::covering({{0, 0}, {300, 300}}, 1.0 + 0.1 * (scene % 5));
    const CullMap cpu = cell_cull_map(grid, samples, occ);
    const CullMap ogl = gl.cell_cull_map(grid, samples, occ, zlo, zhi);
    // OpenGL snaps vertices to 1/256 of a pixel: a pixel centre within two such steps of a
    // shadow's border may fall on either side (the ε coupling keeps that slack, CullMapSettings).
    auto near_border = [&](std::size_t k) {
      const Vec2 c =
          grid.center(static_cast<int>(k % grid.width), static_cast<int>(k / grid.width));
      for (const Vec3& v : samples)
        for (const Occluder& o : occ) {
          bool near = false;
          for_each_shadow(v, o, grid.bounds().grown(grid.pixel), [&](const OccluderShadow& sh) {
            for (std::size_t e = 0; e < sh.polygon.size(); ++e)
              near |=
                  geometry::distance_to_segment(
                      c, sh.polygon[e], sh.polygon[(e + 1) % sh.polygon.size()]) < grid.pixel / 128;
          });
          if (near) return true;
        }
      return false;
    };
    for (std::size_t k = 0; k < cpu.values().size(); ++k) {
      const float a = cpu.values()[k], b = ogl.values()[k];
      ++pixels;
      if (std::isinf(a) != std::isinf(b)) {
        ASSERT_TRUE(near_border(k))
            << "scene " << scene << " pixel " << k << " coverage differs: cpu " << a << " gl " << b;
        ++border_pixels;
        continue;
      }
      if (std::isinf(a)) continue;
      const double exact = std::min<double>(a, zhi);
      if ((b > exact + 1e-9 || b < exact - tol) && near_border(k)) {
        ++border_pixels;
        continue;
      }
      ASSERT_LE(b, exact + 1e-9) << "scene " << scene << " pixel " << k << ": not conservative";
      ASSERT_GE(b, exact - tol) << "scene " << scene << " pixel " << k;
    }
  }
  EXPECT_GT(pixels, 1000000u);
  EXPECT_LT(border_pixels, pixels / 10000) << border_pixels << " of " << pixels;
}

}  // namespace
}  // namespace urbanpvs::preprocess
