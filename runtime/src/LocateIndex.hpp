// SPDX-License-Identifier: MIT
#pragma once

// What a random query walks, laid out at load so that its cache misses overlap. locate() reads
// a grid cell's list of candidates, their shapes, then the found cell's PVS. With the grid's
// offsets and entries apart and an expanded PVS behind its offset table, those were four misses
// that each waited for the one before (about 120 ns each here: runtime_benchmark prints the
// machine's memory latency). A bucket holds a grid cell's list inline, so the list is one miss;
// for an expanded file a second line, fetched with it, names where each candidate's record
// starts, and a record holds the shape and the first ids together (PvsExpansion): all
// candidates' records are fetched at once, so the whole query waits about two misses.

#include <cstdint>
#include <type_traits>

#include "HugePages.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {

/// One grid cell's candidates in one cache line.
struct alignas(64) GridBucket {
  static constexpr std::uint32_t kCapacity = 15;
  /// Candidates (ascending cell indices, as in the grid); above kCapacity the bucket holds none
  /// and locate() reads the grid's own list.
  std::uint32_t count = 0;
  std::uint32_t cell[kCapacity] = {};
};
static_assert(sizeof(GridBucket) == 64);

/// Expanded files only, one per bucket: where bucket.cell[k]'s record starts in
/// PvsExpansion::ids, in records. A line of its own, so that files not expanded do not carry it.
struct alignas(64) BucketRecords {
  std::uint32_t record[GridBucket::kCapacity] = {};
  std::uint32_t unused = 0;
};
static_assert(sizeof(BucketRecords) == 64);
// Records hold shapes as bytes, copied in and out with memcpy.
static_assert(std::is_trivially_copyable_v<CellShape>);

/// The buckets of a loaded file.
struct LocateIndex {
  LargeVector<GridBucket> buckets;     ///< one per grid cell; empty: read the grid's lists
  LargeVector<BucketRecords> records;  ///< one per bucket for expanded files, else empty
};

/// One bucket per grid cell of `grid`; with `expansion`, the records too. Without records
/// (one lies beyond what 32 bits of records reach) `out` stays empty.
void build_locate_index(const GridIndex& grid, const PvsExpansion* expansion, LocateIndex& out);

/// Copies each cell's shape into the head of its expanded record.
void copy_shapes_into_records(const CellTable& cells, PvsExpansion& expansion) noexcept;

}  // namespace urbanpvs::runtime::detail
