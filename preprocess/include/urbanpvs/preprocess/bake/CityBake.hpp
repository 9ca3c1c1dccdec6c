// SPDX-License-Identifier: GPL-3.0-or-later
// From a city to the contents of a PVS file in one call, on the calling thread: the scene, then
// every cell's PVS in cell order. urbanpvs-preprocess does the same in parallel with a journal.
#pragma once

#include <cstdint>
#include <functional>

#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

namespace urbanpvs::preprocess {

struct BakeStats {
  std::size_t blocks = 0, occluders = 0, cells = 0, samples = 0;
  std::uint64_t pvs_entries = 0;
  CellCounters counters;
};

/// Computes every cell's PVS. `progress(done, total)` is called after each cell when given.
/// Throws std::invalid_argument for settings that break the coupling.
runtime::PvsBake bake_city(const geometry::City& city, const BakeOptions& options,
                           BakeStats* stats = nullptr,
                           const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace urbanpvs::preprocess
