// SPDX-License-Identifier: GPL-3.0-or-later
// Cells are independent (thesis 5.2.4): a list of cells, in Hilbert order, is cut into one
// stretch per thread, each thread with its own CellVisibility (and cull-map context), and a
// thread done early takes half of the longest stretch left. Results
// are handed to the caller per cell, so it can store them by cell index and assemble the file
// in cell order: the output does not depend on the thread count or the order cells finish in.
// The same function serves any subset of cells, e.g. the missing ones after a resume, or one
// machine's share of a bake split across machines.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

namespace urbanpvs::preprocess {

struct CellOutcome {
  std::uint32_t cell = 0;
  std::vector<std::uint32_t> pvs;  ///< ascending object indices
  CellCounters counters;           ///< of this cell alone
};

struct ParallelBakeOptions {
  unsigned threads = 1;        ///< worker threads [Limit: >= 1]
  std::size_t max_chunk = 64;  ///< most cells a thread takes at once [Limit: >= 1]
  /// How often `tick` runs on the calling thread while the workers compute. [Units: ms]
  int tick_ms = 100;
};

/// Computes the PVS of every cell in `cells` (each once) on `options.threads` threads and calls
/// `finished` with each result, from the worker that computed it: it must be thread-safe and
/// may take the outcome. `tick(done)`, when given, runs on the calling thread every
/// `tick_ms` and once at the end with the number of cells finished so far. When a worker or
/// `finished` throws, the others stop after their current cell and the first exception is
/// rethrown here once every thread has ended.
void bake_cells(const BakeScene& scene, std::span<const std::uint32_t> cells,
                const ParallelBakeOptions& options,
                const std::function<void(CellOutcome&)>& finished,
                const std::function<void(std::size_t done)>& tick = {});

}  // namespace urbanpvs::preprocess
