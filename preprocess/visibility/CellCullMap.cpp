// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"

#include <algorithm>
#include <memory>

#include "urbanpvs/preprocess/visibility/CpuRasterizer.hpp"
#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"

namespace urbanpvs::preprocess {

void render_sample(const Vec3& sample, std::span<const geometry::Occluder* const> occluders,
                   CullMap& map, CullMapStats* stats) {
  const Box2 clip = map.grid().bounds().grown(map.grid().pixel);
  for (const geometry::Occluder* o : occluders)
    for_each_shadow(sample, *o, clip, [&](const OccluderShadow& shadow) {
      const std::size_t px = rasterize_max(shadow, map);
      if (stats) ++stats->shadows, stats->pixels_written += px;
    });
}

std::vector<const geometry::Occluder*> pointers_to(std::span<const geometry::Occluder> occluders) {
  std::vector<const geometry::Occluder*> out;
  out.reserve(occluders.size());
  for (const geometry::Occluder& o : occluders) out.push_back(&o);
  return out;
}

CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                      std::span<const geometry::Occluder> occluders, CullMapStats* stats) {
  return cell_cull_map(grid, samples, pointers_to(occluders), stats);
}

void render_sample_front_to_back(const Vec3& sample,
                                 std::span<const geometry::Occluder* const> occluders, CullMap& map,
                                 CullMapStats* stats) {
  auto distance2 = [&](const geometry::Occluder* o) {
    const double dx = std::max({0.0, o->bounds.min.x - sample.x, sample.x - o->bounds.max.x});
    const double dy = std::max({0.0, o->bounds.min.y - sample.y, sample.y - o->bounds.max.y});
    return dx * dx + dy * dy;
  };
  std::vector<std::pair<double, const geometry::Occluder*>> order;
  order.reserve(occluders.size());
  for (const geometry::Occluder* o : occluders) order.emplace_back(distance2(o), o);
  // Ties broken by the pointer (the scene's occluder order): deterministic.
  std::sort(order.begin(), order.end());
  const double margin = map.grid().pixel;
  for (const auto& [d2, o] : order) {
    geometry::Box3 box;
    box.xy = o->bounds.grown(margin);
    box.zmin = box.zmax = o->top_high();
    if (hidden_by(map, box)) {
      if (stats) ++stats->occluders_skipped;
      continue;
    }
    render_sample(sample, std::span<const geometry::Occluder* const>(&o, 1), map, stats);
  }
}

void render_sample_unhidden(const Vec3& sample,
                            std::span<const geometry::Occluder* const> occluders, CullMap& map,
                            SampleHorizon& horizon, CullMapStats* stats) {
  horizon.reset(sample);
  std::vector<std::pair<double, const geometry::Occluder*>> order;
  order.reserve(occluders.size());
  for (const geometry::Occluder* o : occluders)
    order.emplace_back(horizon.distance_to(o->bounds), o);
  // Ties broken by the pointer (the scene's occluder order): deterministic.
  std::sort(order.begin(), order.end());
  for (const auto& [d, o] : order) {
    geometry::Box3 box;
    box.xy = o->bounds;
    box.zmin = box.zmax = o->top_high();
    if (horizon.hides(box)) {
      if (stats) ++stats->occluders_skipped;
      continue;
    }
    render_sample(sample, std::span<const geometry::Occluder* const>(&o, 1), map, stats);
    horizon.add(*o);
  }
}

CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                      std::span<const geometry::Occluder* const> occluders, CullMapStats* stats,
                      OccluderSkipping skipping) {
  CullMap cell(grid);
  if (samples.empty()) return cell;
  CullMap one(grid);
  std::unique_ptr<SampleHorizon> horizon;
  if (skipping == OccluderSkipping::BehindHorizon) horizon = std::make_unique<SampleHorizon>();
  for (std::size_t s = 0; s < samples.size(); ++s) {
    one.fill(CullMap::kNothingHidden);
    if (skipping == OccluderSkipping::HiddenInMap)
      render_sample_front_to_back(samples[s], occluders, one, stats);
    else if (skipping == OccluderSkipping::BehindHorizon)
      render_sample_unhidden(samples[s], occluders, one, *horizon, stats);
    else
      render_sample(samples[s], occluders, one, stats);
    if (s == 0) {
      cell.values() = one.values();
    } else {
      std::vector<float>& z = cell.values();
      const std::vector<float>& w = one.values();
      for (std::size_t k = 0; k < z.size(); ++k) z[k] = std::min(z[k], w[k]);
    }
  }
  return cell;
}

}  // namespace urbanpvs::preprocess
