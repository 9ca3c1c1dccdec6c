// SPDX-License-Identifier: GPL-3.0-or-later
// From a city to the contents of a PVS file (thesis 5.2.4): blocks, occluders shrunk by ε, view
// cells with samples every 2ε on their top edges, one cell cull map per cell over the whole
// city (every occluder: the brute-force form; the hierarchical test of thesis 5.6 is issue 5),
// and the objects the map does not hide.
#pragma once

#include <cstdint>
#include <functional>

#include "urbanpvs/geometry/Blocks.hpp"
#include "urbanpvs/geometry/ViewCells.hpp"
#include "urbanpvs/preprocess/CullMap.hpp"
#include "urbanpvs/runtime/pvs_writer.hpp"

namespace urbanpvs::preprocess {

enum class Backend { Cpu, OsMesa };

/// One settings struct for the whole bake; stored in the output (thesis 7.2 couples ε and the
/// pixel size: CullMapSettings::validate).
struct BakeOptions {
  geometry::BlockOptions blocks;
  geometry::ViewCellOptions cells;  ///< cells.epsilon is the ε of shrinking and sampling
  double pixel = 1.39;              ///< cull-map pixel size [Units: m]
  Backend backend = Backend::Cpu;
  /// Occluders are shrunk by this instead of cells.epsilon. Only for tests that must show a
  /// broken bake is caught (urbanpvs-validate); never set it otherwise. [Units: m]
  double shrink_override = -1;
};

struct BakeStats {
  std::size_t blocks = 0, occluders = 0, cells = 0, samples = 0, shadows = 0;
  std::uint64_t pvs_entries = 0;
};

/// Computes every cell's PVS. `progress(done, total)` is called after each cell when given.
/// Throws std::invalid_argument for settings that break the coupling.
runtime::PvsBake bake_city(const geometry::City& city, const BakeOptions& options,
                           BakeStats* stats = nullptr,
                           const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace urbanpvs::preprocess
