// SPDX-License-Identifier: GPL-3.0-or-later
// The PVS of one view cell by the hierarchical occlusion test of thesis 5.6, in two parts.
// Near the cell, cull maps: a small map centred on the cell, grown ×2 per side up to
// BakeOptions::max_map:
//  - values inside a map are final once every occluder that meets the map is rendered: an
//    occluder outside a convex map around the cell casts its shadow away from the cell, never
//    into the map; so objects inside are decided as soon as they lie inside;
//  - occluders hidden in the current map (occluded occluders) or behind its horizon add nothing
//    to any larger map and are dropped (thesis 5.6.1).
// Beyond the largest map, the sample horizons (SampleHorizon): per sample a front-to-back sweep
// over the occluder and object quadtrees, whole districts rejected at once, stopping when every
// open object has been met; pixel centres its sectors cannot decide are traced exactly
// (SightLine). An object is hidden from the cell when it is hidden from every sample: the
// thesis's min-over-samples merge (5.5), taken per object instead of per pixel.
// The brute-force form (one map over the city, every occluder) is kept as the reference.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/visibility/CellCounters.hpp"
#include "urbanpvs/preprocess/visibility/CellMapRenderer.hpp"
#include "urbanpvs/preprocess/visibility/FarField.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

namespace urbanpvs::preprocess {

/// Computes cell PVSs for one thread: owns the renderer (and its OpenGL context) and the
/// per-cell scratch state. Not thread-safe; make one per thread. The scene must outlive it.
class CellVisibility {
 public:
  explicit CellVisibility(const BakeScene& scene);
  ~CellVisibility();
  CellVisibility(const CellVisibility&) = delete;
  CellVisibility& operator=(const CellVisibility&) = delete;

  /// Indices of the objects not proven hidden from `cell`, ascending. Deterministic: the same
  /// cell gives the same list whatever was computed before, on whatever thread.
  std::vector<std::uint32_t> pvs(std::uint32_t cell, CellCounters* counters = nullptr);

 private:
  std::vector<std::uint32_t> hierarchical(std::uint32_t cell, CellCounters& counters);
  std::vector<std::uint32_t> brute_force(std::uint32_t cell, CellCounters& counters);

  const BakeScene& scene_;
  std::unique_ptr<CellMapRenderer> renderer_;
  std::vector<const geometry::Occluder*> all_occluders_;  ///< for the brute-force form
  // Per-cell marks, valid where the stamp equals the current cell's (no clearing per cell).
  std::vector<std::uint32_t> object_decided_, occluder_dropped_, occluder_node_done_;
  std::uint32_t stamp_ = 0;
  FarField far_field_;  ///< beyond the largest map
};

}  // namespace urbanpvs::preprocess
