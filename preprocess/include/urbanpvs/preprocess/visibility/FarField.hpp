// SPDX-License-Identifier: GPL-3.0-or-later
// The far field of the hierarchical test (thesis 5.6): the objects that the cull maps around a
// cell leave open beyond the largest map, decided per sample by a front-to-back sweep over the
// occluder quadtree with the sample's horizon (SampleHorizon). An object is hidden from the cell
// when it is hidden from every sample: the thesis's min-over-samples merge (5.5), taken per
// object instead of per pixel. Nodes and occluders already hidden are skipped whole, whole
// districts of objects are tested at once (the object quadtree), and the sweep of a sample
// stops when every open object has been met. Pixel centres the horizon's sectors cannot decide
// are traced exactly (SightLine), so the far field never hides what the brute-force map shows.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/visibility/CellCounters.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

namespace urbanpvs::preprocess {

/// Per-thread scratch state for the far field of one scene; the scene must outlive it.
class FarField {
 public:
  explicit FarField(const BakeScene& scene);

  /// Of the `open` objects, those not proven hidden from every one of `samples`, in the order
  /// they were found visible. With no occluder, no object tree or no sample, every open object
  /// (nothing proves one hidden). Counts objects_far_field, occluders_far_field, sight_lines.
  std::vector<std::uint32_t> visible(std::span<const Vec3> samples,
                                     std::span<const std::uint32_t> open, CellCounters& counters);

 private:
  struct Event {  ///< the sweep's queue: a node, occluder or object at its distance
    double distance;
    std::uint32_t kind, id;
  };
  const BakeScene& scene_;
  SampleHorizon horizon_;
  std::vector<Event> events_;
  std::vector<std::uint32_t> open_below_;  ///< open objects per object-quadtree node
  // Marks valid where they equal the current call's stamp (no clearing per call).
  std::vector<std::uint32_t> far_visible_, far_open_;
  std::uint32_t stamp_ = 0;
};

}  // namespace urbanpvs::preprocess
