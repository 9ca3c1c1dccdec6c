// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/validate/Validator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

namespace urbanpvs::validate {
namespace {

// The segments of target_seen, counted in `cast`.
//
// Why five segments: a crack is a slot narrower than `crack` between two blockers (walls of
// neighbouring buildings a few millimetres apart, or coincident walls and polygon edges that
// rounding leaves ajar). A segment that threads it runs nearly along the slot, so across the
// segment the slot is at most its width wide; two segments parallel to it and `crack` apart
// across the slot cannot both thread it. The centre segment and its partners ±crack/2 to the
// side (horizontal, across it: vertical walls make vertical slots) and ±crack/2 up and down
// (horizontal slots) therefore never all pass a crack narrower than `crack` in those
// directions (in a slanted direction, narrower than crack·cos 45°). A point seen only through
// such a crack is not counted, as the bake, which fuses buildings closer than its gap
// tolerance, does not count it either.
//
// Why this cannot hide a real miss wider than the crack: every point of the five segments lies
// within crack/2 of the centre segment, from the viewpoint to the target. When the cylinder of
// diameter `crack` around the sight line holds no blocker of another object, all five reach
// their ends and the target is seen. So any sight line to a target through an opening that
// wide is found; a target is left out only when another object comes within crack/2 of its
// sight line, which is a crack by this definition. Targets lie on all surfaces at
// point_spacing, so what stays unchecked is a view of an object through an opening both
// narrower than point_spacing and missing every target, as with any sampling.
bool all_reach(const RayScene& scene, const Vec3& v, const Vec3& q, std::uint32_t object,
               double crack, std::size_t& cast) {
  ++cast;
  if (!scene.reaches(v, q, object)) return false;
  const double dx = q.x - v.x, dy = q.y - v.y, dz = q.z - v.z;
  const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (crack <= 0 || len == 0) return true;
  // Across the segment: side (horizontal) and up (in the vertical plane through it).
  double sx = -dy, sy = dx;
  const double side_len = std::hypot(sx, sy);
  if (side_len < 1e-9 * len)
    sx = 1, sy = 0;  // a vertical segment: any horizontal direction is across it
  else
    sx /= side_len, sy /= side_len;
  // up = side × direction / len, a unit vector across the segment and the side direction.
  const double ux = (sy * dz) / len, uy = (-sx * dz) / len, uz = (sx * dy - sy * dx) / len;
  const double r = 0.5 * crack;
  const double offsets[4][3] = {{r * sx, r * sy, 0},
                                {-r * sx, -r * sy, 0},
                                {r * ux, r * uy, r * uz},
                                {-r * ux, -r * uy, -r * uz}};
  for (const auto& o : offsets) {
    ++cast;
    if (!scene.reaches({v.x + o[0], v.y + o[1], v.z + o[2]}, {q.x + o[0], q.y + o[1], q.z + o[2]},
                       object))
      return false;
  }
  return true;
}

// The objects the rays of a cube map around v meet first, with the points where they meet them.
void cube_map_met(const RayScene& scene, const Vec3& v, int res, double reach,
                  std::vector<std::pair<std::uint32_t, Vec3>>& met, std::size_t& rays) {
  std::vector<std::pair<std::uint32_t, double>> along;
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < res; ++i)
      for (int j = 0; j < res; ++j) {
        const double s = 2 * (i + 0.5) / res - 1, t = 2 * (j + 0.5) / res - 1;
        double d[3];
        const int axis = face / 2;
        const double sign = face % 2 ? -1 : 1;
        d[axis] = sign, d[(axis + 1) % 3] = s, d[(axis + 2) % 3] = t;
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const Vec3 q{v.x + reach * d[0] / len, v.y + reach * d[1] / len, v.z + reach * d[2] / len};
        along.clear();
        scene.first_met(v, q, along);
        ++rays;
        for (const auto& [object, u] : along)
          met.push_back(
              {object, {v.x + u * (q.x - v.x), v.y + u * (q.y - v.y), v.z + u * (q.z - v.z)}});
      }
}

}  // namespace

std::vector<Vec3> target_points(const geometry::CityObject& o, double spacing) {
  std::vector<Vec3> pts;
  if (RayScene::blocks(o)) {
    for (const geometry::Surface3& s : o.surfaces)
      for (const Vec3& p : surface_points(s, spacing)) pts.push_back(p);
  } else {
    pts = box_points(o.bbox, spacing);
  }
  auto key = [](const Vec3& p) {
    return std::array<long long, 3>{std::llround(p.x * 1e4), std::llround(p.y * 1e4),
                                    std::llround(p.z * 1e4)};
  };
  std::sort(pts.begin(), pts.end(), [&](const Vec3& a, const Vec3& b) { return key(a) < key(b); });
  pts.erase(std::unique(pts.begin(), pts.end(),
                        [&](const Vec3& a, const Vec3& b) { return key(a) == key(b); }),
            pts.end());
  return pts;
}

double lowest_viewpoint(const runtime::CellGeometry& c, const RayScene& scene, double eye_min,
                        Vec2 at) {
  return std::min(c.z_max, std::max(c.z_min, scene.ground_at(at) + eye_min));
}

Vec3 random_viewpoint(const runtime::CellGeometry& c, bool top, const RayScene& scene,
                      double eye_min, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  double r1 = std::sqrt(u(rng)), r2 = u(rng);
  const auto& t = c.triangle;
  const double x = (1 - r1) * t[0].x + r1 * (1 - r2) * t[1].x + r1 * r2 * t[2].x;
  const double y = (1 - r1) * t[0].y + r1 * (1 - r2) * t[1].y + r1 * r2 * t[2].y;
  if (top) return {x, y, c.z_max};
  const double low = lowest_viewpoint(c, scene, eye_min, {x, y});
  return {x, y, low + u(rng) * (c.z_max - low)};
}

const Vec3* first_target_seen(const RayScene& scene, const Vec3& v,
                              const std::vector<Vec3>& targets, std::uint32_t object, double crack,
                              std::size_t* rays) {
  for (const Vec3& q : targets)
    if (target_seen(scene, v, q, object, crack, rays)) return &q;
  return nullptr;
}

bool target_seen(const RayScene& scene, const Vec3& v, const Vec3& q, std::uint32_t object,
                 double crack, std::size_t* rays) {
  std::size_t cast = 0;
  const bool seen = all_reach(scene, v, q, object, crack, cast);
  if (rays) *rays += cast;
  return seen;
}

void ValidationOptions::validate() const {
  if (cube_resolution < 1 || cube_resolution > 1024)
    throw std::invalid_argument("cube resolution must be 1 .. 1024");
  if (!(point_spacing >= 0.1 && point_spacing <= 1000))
    throw std::invalid_argument("point spacing must be 0.1 .. 1000 m");
  if (!(crack >= 0 && crack <= 1)) throw std::invalid_argument("crack must be 0 .. 1 m");
  if (tightness_cells > 1'000'000)
    throw std::invalid_argument("tightness cells must be 0 .. 1000000");
  if (viewpoints_per_cell < 1 || viewpoints_per_cell > 1024)
    throw std::invalid_argument("viewpoints per cell must be 1 .. 1024");
}

CellTightnessStats cell_tightness_stats(const std::vector<CellTightness>& cells) {
  CellTightnessStats s;
  std::vector<double> ratios;
  for (const CellTightness& c : cells) {
    if (c.seen == 0) {
      ++s.saw_nothing;
      continue;
    }
    ratios.push_back(double(c.pvs) / double(c.seen));
    s.mean += ratios.back();
  }
  s.cells = ratios.size();
  if (ratios.empty()) return s;
  s.mean /= double(ratios.size());
  std::sort(ratios.begin(), ratios.end());
  // The nearest rank: the smallest ratio that at least that share of the cells does not exceed.
  auto rank = [&](double q) {
    const auto k = static_cast<std::size_t>(std::ceil(q * double(ratios.size())));
    return ratios[std::max<std::size_t>(k, 1) - 1];
  };
  s.median = rank(0.5);
  s.p90 = rank(0.9);
  return s;
}

std::string cell_tightness_csv(const std::vector<CellTightness>& cells) {
  std::string out = "cell,pvs,seen,tightness\n";
  char ratio[32];
  for (const CellTightness& c : cells) {
    ratio[0] = '\0';
    if (c.seen > 0) std::snprintf(ratio, sizeof ratio, "%.4f", double(c.pvs) / double(c.seen));
    out += std::to_string(c.cell) + ',' + std::to_string(c.pvs) + ',' + std::to_string(c.seen) +
           ',' + ratio + '\n';
  }
  return out;
}

namespace {

// Looks from viewpoints of cells against the ray scene: what each sees, and the misses.
class Looker {
 public:
  Looker(const geometry::City& city, const RayScene& scene, const ValidationOptions& options,
         ValidationReport& report)
      : city_(city), scene_(scene), options_(options), report_(report) {
    for (const geometry::CityObject& o : city.objects)
      points_.push_back(target_points(o, options.point_spacing));
    reach_ = 2 * std::hypot(scene.bounds().max.x - scene.bounds().min.x,
                            scene.bounds().max.y - scene.bounds().min.y) +
             1000;
  }

  /// From v in `cell`, whose PVS is marked in in_pvs: every object missing from the PVS (a miss
  /// when seen) and, when `measure`, every object in it too, then the objects the rays of a cube
  /// map meet first. An object marked in `seen` already is not looked at again; one newly seen
  /// is marked and appended to seen_list.
  void look(std::uint32_t cell, const Vec3& v, const std::vector<char>& in_pvs, bool measure,
            std::vector<char>& seen, std::vector<std::uint32_t>& seen_list) {
    auto record_seen = [&](std::uint32_t o, const Vec3& at) {
      seen[o] = 1;
      seen_list.push_back(o);
      if (!in_pvs[o]) report_.misses.push_back({cell, v, o, city_.objects[o].source_id, at});
    };
    for (std::uint32_t o = 0; o < city_.objects.size(); ++o) {
      if (seen[o] || (in_pvs[o] && !measure)) continue;
      if (const Vec3* q =
              first_target_seen(scene_, v, points_[o], o, options_.crack, &report_.rays))
        record_seen(o, *q);
    }
    ++report_.viewpoints;
    if (!measure) return;
    // The cube map's rays meet real surfaces: what one meets first is seen there, when the
    // crack test agrees; absent from the PVS, it is a miss the targets fell between.
    met_.clear();
    cube_map_met(scene_, v, options_.cube_resolution, reach_, met_, report_.rays);
    for (const auto& [o, at] : met_)
      if (!seen[o] && all_reach(scene_, v, at, o, options_.crack, report_.rays)) record_seen(o, at);
  }

 private:
  const geometry::City& city_;
  const RayScene& scene_;
  const ValidationOptions& options_;
  ValidationReport& report_;
  std::vector<std::vector<Vec3>> points_;
  double reach_ = 0;
  std::vector<std::pair<std::uint32_t, Vec3>> met_;
};

// Distinct random cells, `wanted` of them or all: the first of a random permutation.
std::vector<std::uint32_t> distinct_cells(std::uint32_t count, std::size_t wanted,
                                          std::mt19937_64& rng) {
  if (wanted == 0) return {};
  std::vector<std::uint32_t> cells(count);
  for (std::uint32_t c = 0; c < count; ++c) cells[c] = c;
  const std::size_t n = std::min<std::size_t>(wanted, count);
  for (std::size_t i = 0; i < n; ++i) {
    const auto j = std::uniform_int_distribution<std::size_t>(i, count - 1)(rng);
    std::swap(cells[i], cells[j]);
  }
  cells.resize(n);
  return cells;
}

}  // namespace

ValidationReport validate(const geometry::City& city, const runtime::PvsFile& pvs,
                          const ValidationOptions& options, const TightnessObserver& observer) {
  options.validate();
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

  const RayScene scene(city);
  ValidationReport report;
  Looker looker(city, scene, options, report);
  const double eye_min = pvs.settings().eye_min_m;  // a viewer stands this high on the terrain
  runtime::PvsDecoder decoder(pvs);
  std::vector<char> in_pvs(city.objects.size()), seen(city.objects.size());
  std::vector<std::uint32_t> seen_list, pvs_list;
  auto open_cell = [&](std::uint32_t cell, runtime::CellGeometry& geometry) {
    pvs.cell(cell, geometry);
    if (decoder.decode(cell) != runtime::Status::kOk)
      throw std::runtime_error("cannot decode the PVS of cell " + std::to_string(cell));
    std::fill(in_pvs.begin(), in_pvs.end(), 0);
    std::fill(seen.begin(), seen.end(), 0);
    seen_list.clear();
    for (std::uint32_t o : decoder) in_pvs[o] = 1;
  };
  std::mt19937_64 rng(options.seed);
  for (std::size_t n = 0; n < options.viewpoints; ++n) {
    const auto cell = static_cast<std::uint32_t>(
        std::uniform_int_distribution<std::uint64_t>(0, pvs.cell_count() - 1)(rng));
    runtime::CellGeometry geometry;
    open_cell(cell, geometry);
    const Vec3 v = random_viewpoint(geometry, n % 2 == 0, scene, eye_min, rng);
    const bool measure = n < options.tightness_viewpoints;
    looker.look(cell, v, in_pvs, measure, seen, seen_list);
    if (measure) {
      report.pvs_total += decoder.size();
      report.seen_total += seen_list.size();
      if (observer) {
        pvs_list.assign(decoder.begin(), decoder.end());
        observer({cell, v, pvs_list, seen});
      }
    }
  }
  // The cells are drawn first and each has its own stream of viewpoints (from the seed and the
  // cell), so more viewpoints per cell add to the same first ones: the union only grows.
  std::mt19937_64 cell_rng(options.seed ^ 0x6a09e667f3bcc909u);
  for (std::uint32_t cell : distinct_cells(pvs.cell_count(), options.tightness_cells, cell_rng)) {
    runtime::CellGeometry geometry;
    open_cell(cell, geometry);
    std::mt19937_64 viewpoint_rng(options.seed * 0x9e3779b97f4a7c15u + cell);
    for (std::size_t k = 0; k < options.viewpoints_per_cell; ++k) {
      const Vec3 v = random_viewpoint(geometry, k % 2 == 0, scene, eye_min, viewpoint_rng);
      looker.look(cell, v, in_pvs, true, seen, seen_list);
    }
    report.cells.push_back({cell, decoder.size(), seen_list.size()});
  }
  return report;
}

}  // namespace urbanpvs::validate
