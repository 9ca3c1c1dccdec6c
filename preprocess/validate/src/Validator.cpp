// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/validate/Validator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <stdexcept>

namespace urbanpvs::validate {
namespace {

// Points certainly inside or on a building: on the walls of its occluder prisms (ground
// footprint up to the lowest roof point) and inside them. Any unblocked ray to such a point
// first meets the real building somewhere, so the building is really visible.
std::vector<Point3> target_points(const geometry::CityObject& o, double spacing) {
  std::vector<Point3> pts;
  for (const geometry::OccluderPrism& p : o.occluders) {
    const double lo = p.ground_z + 0.05, hi = p.top_z - 0.01;
    const double heights[] = {lo, 0.5 * (lo + hi), hi};
    geometry::for_each_edge(p.footprint, [&](Vec2 a, Vec2 b) {
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
      // Slightly inside the wall, so a ray grazing the wall line is not counted.
      const Vec2 inward = (1e-3 / std::max(len, 1e-9)) * Vec2{a.y - b.y, b.x - a.x};
      for (int k = 0; k <= n; ++k) {
        const Vec2 q = a + (double(k) / n) * (b - a) + inward;
        for (double z : heights) pts.push_back({q.x, q.y, z});
      }
    });
  }
  return pts;
}

Point3 random_viewpoint(const runtime::CellGeometry& c, bool top, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  double r1 = std::sqrt(u(rng)), r2 = u(rng);
  const auto& t = c.triangle;
  const double x = (1 - r1) * t[0].x + r1 * (1 - r2) * t[1].x + r1 * r2 * t[2].x;
  const double y = (1 - r1) * t[0].y + r1 * (1 - r2) * t[1].y + r1 * r2 * t[2].y;
  const double z = top ? c.z_max : c.z_min + u(rng) * (c.z_max - c.z_min);
  return {x, y, z};
}

void cube_map_seen(const RayScene& scene, const Point3& v, int res, double reach,
                   std::vector<std::uint32_t>& seen, std::size_t& rays) {
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < res; ++i)
      for (int j = 0; j < res; ++j) {
        const double s = 2 * (i + 0.5) / res - 1, t = 2 * (j + 0.5) / res - 1;
        double d[3];
        const int axis = face / 2;
        const double sign = face % 2 ? -1 : 1;
        d[axis] = sign, d[(axis + 1) % 3] = s, d[(axis + 2) % 3] = t;
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const Point3 q{v.x + reach * d[0] / len, v.y + reach * d[1] / len,
                       v.z + reach * d[2] / len};
        scene.seen_along(v, q, seen);
        ++rays;
      }
}

}  // namespace

ValidationReport validate(const geometry::City& city, const runtime::PvsFile& pvs,
                          const ValidationOptions& options) {
  if (pvs.object_count() != city.objects.size())
    throw std::runtime_error("the PVS file has " + std::to_string(pvs.object_count()) +
                             " objects, the city " + std::to_string(city.objects.size()));
  for (std::uint32_t i = 0; i < pvs.object_count(); ++i) {
    runtime::ObjectInfo info;
    if (pvs.object(i, info) != runtime::Status::kOk || info.source_id != city.objects[i].source_id)
      throw std::runtime_error("object " + std::to_string(i) + " of the PVS file is not " +
                               city.objects[i].source_id);
  }
  if (pvs.cell_count() == 0) throw std::runtime_error("the PVS file has no cells");

  // Cracks narrower than the bake's block gap tolerance are closed, as in the bake (documented
  // input semantics: such gaps are digitizing slivers between buildings sharing a wall).
  double gap = 0;
  for (std::size_t i = 0; i < pvs.property_count(); ++i) {
    std::string_view key, value;
    if (pvs.property(i, key, value) == runtime::Status::kOk && key == "gap_tolerance_m")
      gap = std::strtod(std::string(value).c_str(), nullptr);
  }
  const RayScene scene(city, std::max(RayScene::kSharedWall, 0.5 * gap));
  std::vector<std::vector<Point3>> points;
  for (const geometry::CityObject& o : city.objects)
    points.push_back(target_points(o, options.point_spacing));
  const double reach = 2 * std::hypot(scene.bounds().max.x - scene.bounds().min.x,
                                      scene.bounds().max.y - scene.bounds().min.y) +
                       1000;

  ValidationReport report;
  std::mt19937_64 rng(options.seed);
  runtime::PvsDecoder decoder(pvs);
  std::vector<char> in_pvs(city.objects.size());
  std::vector<std::uint32_t> seen;
  for (std::size_t n = 0; n < options.viewpoints; ++n) {
    const auto cell = static_cast<std::uint32_t>(
        std::uniform_int_distribution<std::uint64_t>(0, pvs.cell_count() - 1)(rng));
    runtime::CellGeometry geometry;
    pvs.cell(cell, geometry);
    const Point3 v = random_viewpoint(geometry, n % 2 == 0, rng);
    if (decoder.decode(cell) != runtime::Status::kOk)
      throw std::runtime_error("cannot decode the PVS of cell " + std::to_string(cell));
    std::fill(in_pvs.begin(), in_pvs.end(), 0);
    for (std::uint32_t o : decoder) in_pvs[o] = 1;
    const bool measure = n < options.tightness_viewpoints;
    seen.clear();
    for (std::uint32_t o = 0; o < city.objects.size(); ++o) {
      if (in_pvs[o] && !measure) continue;
      for (const Point3& q : points[o]) {
        ++report.rays;
        if (scene.blocked(v, q, o)) continue;
        if (!in_pvs[o]) report.misses.push_back({cell, v, o, city.objects[o].source_id, q});
        seen.push_back(o);
        break;
      }
    }
    if (measure) {
      cube_map_seen(scene, v, options.cube_resolution, reach, seen, report.rays);
      std::sort(seen.begin(), seen.end());
      seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
      // Cube-map hits only count for tightness: targets reach the highest roof point over the
      // whole footprint, which may be air under a gable, so they prove nothing about misses.
      report.pvs_total += decoder.size();
      report.seen_total += seen.size();
    }
    ++report.viewpoints;
  }
  return report;
}

}  // namespace urbanpvs::validate
