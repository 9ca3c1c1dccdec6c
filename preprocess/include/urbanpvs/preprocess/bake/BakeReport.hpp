// SPDX-License-Identifier: GPL-3.0-or-later
// What a finished bake reports: the JSON report (--report) and the summary on standard error
// come from this one struct, so they never disagree.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

namespace urbanpvs::preprocess {

/// Wall-clock seconds per stage.
struct StageSeconds {
  double read = 0;        ///< reading and hashing the inputs and the region
  double scene = 0;       ///< blocks, shrunk occluders, view cells, indices (BakeScene)
  double visibility = 0;  ///< every cell's PVS, including the journal
  double write = 0;       ///< encoding and writing the file (and the report)
  double total() const { return read + scene + visibility + write; }
};

struct InputFileInfo {
  std::string path;
  std::uint64_t bytes = 0;
};

/// What one rank did in a distributed bake.
struct RankShare {
  std::size_t cells = 0;         ///< cells it computed
  unsigned threads = 0;          ///< its worker threads
  std::uint64_t peak_bytes = 0;  ///< its peak resident memory, as last reported
};

struct BakeReport {
  std::string tool;  ///< "urbanpvs-preprocess <version>"
  std::vector<InputFileInfo> inputs;
  std::uint64_t input_hash = 0;   ///< as stored in the file (hash_input_files)
  std::uint64_t fingerprint = 0;  ///< as stored in the journal (bake_fingerprint)
  std::string output;
  std::uint64_t output_bytes = 0;
  /// The settings stored in the file's metadata properties, in their order.
  std::vector<std::pair<std::string, std::string>> settings;
  unsigned threads = 1;  ///< of this process (rank 0 in an MPI job)
  /// Each rank's share in an MPI job (DistributedBake.hpp); empty for a run of one process.
  std::vector<RankShare> ranks;
  std::size_t objects = 0, blocks = 0, occluders = 0, cells = 0;
  std::size_t terrain_occluders = 0;     ///< of `occluders`, the terrain's levels (--terrain-step)
  std::size_t roof_plane_occluders = 0;  ///< of `occluders`, under roof faces (--sloped-roofs)
  /// Of `occluders`, the levels of buildings shrunk in 3D (--solid-step); the buildings that
  /// gave some, and why the others gave none (reason -> buildings).
  std::size_t solid_occluders = 0, solids_shrunk = 0;
  std::map<std::string, std::size_t> solids_declined;
  /// What reading had to do, one line each (ReadReport::repairs, ReadReport::non_occluding),
  /// and what it warns of (ReadReport::warnings).
  std::vector<std::string> repairs, non_occluding, warnings;
  std::size_t multipolygons = 0;  ///< buildings assembled from OSM multipolygon relations
  std::string terrain;            ///< ReadReport::terrain_note; empty without a DEM
  double cell_area = 0;           ///< the view cells' summed area, free space in their region [m²]
  std::size_t cells_computed = 0;      ///< by this run
  std::size_t cells_from_journal = 0;  ///< taken from a resumed journal
  std::uint64_t pvs_entries = 0;       ///< sum of PVS sizes over all cells
  std::uint64_t pvs_max = 0;
  StageSeconds seconds;
  CellCounters counters;  ///< summed over every cell, journal cells included
  std::uint64_t peak_memory_bytes = 0;

  double mean_pvs() const { return cells > 0 ? double(pvs_entries) / double(cells) : 0.0; }
  /// 1 − mean PVS / objects: the share of objects a renderer skips in the average cell.
  double fraction_culled() const { return objects > 0 ? 1.0 - mean_pvs() / double(objects) : 0.0; }
  /// The most cells one rank computed over the mean of all ranks (1: perfect balance); 1 for a
  /// run of one process.
  double load_balance() const {
    std::size_t most = 0, sum = 0;
    for (const RankShare& r : ranks) most = std::max(most, r.cells), sum += r.cells;
    return sum > 0 ? double(most) * double(ranks.size()) / double(sum) : 1.0;
  }
  /// Cells computed by this run per second of the visibility stage.
  double cells_per_second() const {
    return seconds.visibility > 0 ? double(cells_computed) / seconds.visibility : 0.0;
  }
};

/// The report as pretty-printed JSON (see README, "Report"). Settings whose text is a JSON
/// number or boolean appear as such, the others as strings.
std::string report_json(const BakeReport& report);

/// The human summary printed on standard error, several lines, each ending in '\n'.
std::string summary_text(const BakeReport& report);

/// The process's peak resident memory so far (getrusage ru_maxrss). [Units: bytes]
std::uint64_t peak_memory_bytes();

}  // namespace urbanpvs::preprocess
