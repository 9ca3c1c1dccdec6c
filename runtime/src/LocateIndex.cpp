// SPDX-License-Identifier: MIT
#include "LocateIndex.hpp"

#include <algorithm>
#include <cstring>

namespace urbanpvs::runtime::detail {

void build_locate_index(const GridIndex& grid, const PvsExpansion* expansion, LocateIndex& out) {
  const std::size_t grid_cells = grid.offsets.empty() ? 0 : grid.offsets.size() - 1;
  out.buckets.assign(grid_cells, GridBucket{});
  if (expansion != nullptr) out.records.assign(grid_cells, BucketRecords{});
  for (std::size_t g = 0; g < grid_cells; ++g) {
    GridBucket& b = out.buckets[g];
    const std::uint32_t begin = grid.offsets[g], end = grid.offsets[g + 1];
    b.count = end - begin;
    if (b.count > GridBucket::kCapacity) continue;
    for (std::uint32_t k = 0; k < b.count; ++k) {
      const std::uint32_t cell = grid.entries[begin + k];
      b.cell[k] = cell;
      if (expansion == nullptr) continue;
      const std::uint64_t record = expansion->record(cell);
      if (record > UINT32_MAX) {
        out = LocateIndex{};
        return;
      }
      out.records[g].record[k] = static_cast<std::uint32_t>(record);
    }
  }
}

void copy_shapes_into_records(const CellTable& cells, PvsExpansion& expansion) noexcept {
  for (std::uint32_t c = 0; c < cells.count; ++c) {
    std::uint32_t* head = expansion.ids.data() + expansion.offsets[c] - PvsExpansion::kHeaderWords;
    std::memcpy(head, &cells.shapes[c], sizeof(CellShape));
  }
}

}  // namespace urbanpvs::runtime::detail
