// SPDX-License-Identifier: GPL-3.0-or-later
// Every cell's PVS as the bake finds it, held until the file is written. As vectors of 32-bit
// indices they took cells x mean PVS x 4 bytes: 2.7 GB for Liechtenstein's 181,676 street cells,
// each seeing all 3,723 buildings (none has a height, so none occludes), for a file of 4.9 MB;
// a larger city of that kind would not fit in memory at all. Each list is kept instead as the
// smaller of its gaps in LEB128 varints (a byte per entry of a dense list) and a bitset over the
// objects (an eighth of a byte per object), and the writer decodes the lists as it goes
// (runtime::PvsBake::pvs_source).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace urbanpvs::preprocess {

class CompactPvsStore {
 public:
  CompactPvsStore() = default;
  CompactPvsStore(std::size_t cells, std::uint32_t objects);

  std::size_t cells() const { return lists_.size(); }
  /// Keeps `pvs` (strictly increasing indices below the object count) as cell `cell`'s list,
  /// replacing what it held. Threads may store at once, each into cells of its own.
  void store(std::uint32_t cell, std::span<const std::uint32_t> pvs);
  /// Cell `cell`'s list (empty until stored).
  void load(std::uint32_t cell, std::vector<std::uint32_t>& pvs) const;
  std::vector<std::uint32_t> load(std::uint32_t cell) const;
  /// The number of objects in cell `cell`'s list.
  std::uint32_t size(std::uint32_t cell) const { return sizes_[cell]; }
  /// Bytes the lists take (without the per-cell bookkeeping).
  std::size_t bytes() const;

 private:
  std::uint32_t objects_ = 0;
  std::vector<std::vector<unsigned char>> lists_;  ///< per cell: a kind byte, then the list
  std::vector<std::uint32_t> sizes_;
};

}  // namespace urbanpvs::preprocess
