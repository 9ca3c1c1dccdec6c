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
#include "urbanpvs/preprocess/visibility/CellMapRenderer.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

namespace urbanpvs::preprocess {

/// Where the time of one cell (or, summed, of a bake) goes.
struct CellCounters {
  std::uint64_t cells = 0;                     ///< cells these counters sum over
  std::uint64_t maps = 0;                      ///< cull maps rendered (steps of the growth)
  std::uint64_t map_pixels = 0;                ///< pixels of those maps, summed
  std::uint64_t largest_map = 0;               ///< longest side of the largest map [pixels]
  std::uint64_t early_breaks = 0;              ///< cells that stopped before covering the city
  std::uint64_t occluders_considered = 0;      ///< occluder tests (an occluder once per map)
  std::uint64_t occluders_rendered = 0;        ///< occluders drawn into a map, summed over maps
  std::uint64_t occluders_occluded = 0;        ///< dropped: hidden inside the previous map
  std::uint64_t occluders_behind_horizon = 0;  ///< dropped: hidden behind the previous horizon
  std::uint64_t objects_in_map = 0;            ///< objects decided by the map's heights
  std::uint64_t nodes_behind_horizon = 0;      ///< quadtree nodes rejected whole
  std::uint64_t objects_far_field = 0;         ///< objects left to the sample horizons
  std::uint64_t occluders_far_field = 0;       ///< occluders added to them (over samples)
  std::uint64_t sight_lines = 0;               ///< pixel centres traced exactly (SightLine)
  std::uint64_t shadows = 0;                   ///< shadow polygons rasterized
  std::uint64_t pixels_written = 0;            ///< by the CPU rasterizer

  CellCounters& operator+=(const CellCounters& o);
};

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
  void far_field(std::span<const Vec3> samples, std::span<const std::uint32_t> objects_open,
                 CellCounters& counters);

  const BakeScene& scene_;
  std::unique_ptr<CellMapRenderer> renderer_;
  std::vector<const geometry::Occluder*> all_occluders_;  ///< for the brute-force form
  // Per-cell marks, valid where the stamp equals the current cell's (no clearing per cell).
  std::vector<std::uint32_t> object_decided_, occluder_dropped_, occluder_node_done_, far_visible_,
      far_open_;
  SampleHorizon horizon_;
  struct FarEvent {  ///< far_field's sweep: a node, occluder or object at its distance
    double distance;
    std::uint32_t kind, id;
  };
  std::vector<FarEvent> far_events_;
  std::vector<std::uint32_t> open_below_;  ///< open objects per object-quadtree node
  std::uint32_t stamp_ = 0;
};

}  // namespace urbanpvs::preprocess
