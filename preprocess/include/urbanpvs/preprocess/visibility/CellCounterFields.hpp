// SPDX-License-Identifier: GPL-3.0-or-later
// CellCounters as named fields in one fixed order: the journal stores the counters in this order
// and the report names them so. The static_assert stops a new counter from being dropped
// silently by both.
#pragma once

#include <array>
#include <cstdint>
#include <utility>

#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

namespace urbanpvs::preprocess {

inline constexpr std::array<std::pair<const char*, std::uint64_t CellCounters::*>, 16>
    kCellCounterFields = {{
        {"cells", &CellCounters::cells},
        {"maps", &CellCounters::maps},
        {"map_pixels", &CellCounters::map_pixels},
        {"largest_map", &CellCounters::largest_map},
        {"early_breaks", &CellCounters::early_breaks},
        {"occluders_considered", &CellCounters::occluders_considered},
        {"occluders_rendered", &CellCounters::occluders_rendered},
        {"occluders_occluded", &CellCounters::occluders_occluded},
        {"occluders_behind_horizon", &CellCounters::occluders_behind_horizon},
        {"objects_in_map", &CellCounters::objects_in_map},
        {"nodes_behind_horizon", &CellCounters::nodes_behind_horizon},
        {"objects_far_field", &CellCounters::objects_far_field},
        {"occluders_far_field", &CellCounters::occluders_far_field},
        {"sight_lines", &CellCounters::sight_lines},
        {"shadows", &CellCounters::shadows},
        {"pixels_written", &CellCounters::pixels_written},
    }};

static_assert(sizeof(CellCounters) == kCellCounterFields.size() * sizeof(std::uint64_t),
              "CellCounters changed: list every field in kCellCounterFields (and bump the "
              "journal version when the journal's counters change)");

}  // namespace urbanpvs::preprocess
