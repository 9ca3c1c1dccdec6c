// SPDX-License-Identifier: GPL-3.0-or-later
// The cells of one bake across the ranks of an MPI job. Cells are independent (thesis 5.2.4), so
// every rank builds the same scene from the same inputs and computes whatever cells rank 0 hands
// it. Rank 0 hands out chunks as ranks ask for more (dynamic self-scheduling: a rank that meets
// a slow district simply asks less often; chunks shrink towards the end so that the ranks
// finish together), computes chunks itself between answering, and gets every finished cell
// back in the journal's checksummed record encoding (BakeJournal.hpp), which it appends to the
// journal and keeps. Rank 0 assembles the file in cell order, so its bytes depend neither on
// the number of ranks or threads nor on who computed what.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "urbanpvs/preprocess/bake/BakeJournal.hpp"
#include "urbanpvs/preprocess/bake/BakeReport.hpp"
#include "urbanpvs/preprocess/bake/MpiJob.hpp"
#include "urbanpvs/preprocess/bake/ParallelBake.hpp"

namespace urbanpvs::preprocess {

/// Rank 0: computes `cells` (each once) across every rank of `job`, `options.threads` threads
/// on this rank; `finished` gets every outcome (on a worker thread for this rank's cells, on
/// the calling thread for the others'), `tick(done)` runs on the calling thread with the number
/// of cells finished so far. Returns each rank's share. Other ranks: compute what rank 0 hands
/// out until it says there is no more; `cells`, `finished` and `tick` are not used, and the
/// result is empty. `identity` must be the same on every rank (the caller checks it).
std::vector<RankShare> bake_cells_across_ranks(const MpiJob& job, const BakeScene& scene,
                                               const JournalIdentity& identity,
                                               std::span<const std::uint32_t> cells,
                                               const ParallelBakeOptions& options,
                                               const std::function<void(CellOutcome&)>& finished,
                                               const std::function<void(std::size_t)>& tick);

/// The size of the next chunk for a rank of `threads` threads when `remaining` cells are left
/// for `ranks` ranks: at most 32 cells per thread (a few seconds of work), and no more than
/// half of a fair share of what is left, so that the last chunks are small.
std::size_t chunk_size(std::size_t remaining, int ranks, unsigned threads);

}  // namespace urbanpvs::preprocess
