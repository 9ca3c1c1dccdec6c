// SPDX-License-Identifier: GPL-3.0-or-later
// The counters of the hierarchical test, and their names in one fixed order: the journal stores
// the counters in this order, the report names them so, and summing goes over the same list.
// The static_assert stops a new counter from being dropped silently by all three.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

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
  std::uint64_t sample_sweeps = 0;             ///< far-field sweeps, one sample each
  std::uint64_t narrow_sweeps = 0;   ///< of them, those that watched only their asked objects
  std::uint64_t sweeps_spared = 0;   ///< samples whose kept answers (FarField) made one needless
  std::uint64_t shadows = 0;         ///< shadow polygons rasterized
  std::uint64_t pixels_written = 0;  ///< by the CPU rasterizer

  CellCounters& operator+=(const CellCounters& o);
};

inline constexpr std::array<std::pair<const char*, std::uint64_t CellCounters::*>, 19>
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
        {"sample_sweeps", &CellCounters::sample_sweeps},
        {"narrow_sweeps", &CellCounters::narrow_sweeps},
        {"sweeps_spared", &CellCounters::sweeps_spared},
        {"shadows", &CellCounters::shadows},
        {"pixels_written", &CellCounters::pixels_written},
    }};

static_assert(sizeof(CellCounters) == kCellCounterFields.size() * sizeof(std::uint64_t),
              "CellCounters changed: list every field in kCellCounterFields (and bump the "
              "journal version when the journal's counters change)");

/// Sums the counters; largest_map takes the maximum.
inline CellCounters& CellCounters::operator+=(const CellCounters& o) {
  for (const auto& [name, member] : kCellCounterFields)
    this->*member = member == &CellCounters::largest_map ? std::max(this->*member, o.*member)
                                                         : this->*member + o.*member;
  return *this;
}

}  // namespace urbanpvs::preprocess
