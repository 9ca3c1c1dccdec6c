// SPDX-License-Identifier: MIT
// Set operations over decoded PVSs for streaming engines: the union of several cells (what to
// prefetch around the camera or along a planned route) and the delta between two cells (what
// enters and what leaves view when the camera crosses from one to the other).
#include <algorithm>
#include <new>

#include "Bits.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace urbanpvs::runtime {

bool PvsDecoder::reserve_sets(std::size_t slots) noexcept {
  if (sets_capacity_ >= slots) return true;
  sets_.reset(new (std::nothrow) std::uint32_t[std::max<std::size_t>(slots, 1)]);
  sets_capacity_ = sets_ ? slots : 0;
  return sets_ != nullptr;
}

Status PvsDecoder::decode_union(const std::uint32_t* cells, std::size_t n) noexcept {
  clear();
  if (n == 0) return Status::kOk;
  if (cells == nullptr) return Status::kInvalidArgument;
  for (std::size_t i = 0; i < n; ++i)
    if (cells[i] >= file_->cell_count()) return Status::kOutOfRange;
  if (n == 1) return decode(cells[0]);
  // One bit per object: marking is O(1) per entry whatever the cells' overlap, and reading the
  // marks back in word order gives the union sorted, with no merge of n lists.
  const std::size_t words = (std::size_t{file_->object_count()} + 31) / 32;
  if (!marks_) {
    marks_.reset(new (std::nothrow) std::uint32_t[std::max<std::size_t>(words, 1)]());
    if (!marks_) return Status::kOutOfMemory;
  }
  if (!reserve_sets(file_->object_count())) return Status::kOutOfMemory;
  for (std::size_t i = 0; i < n; ++i) {
    IndexSpan list;
    const Status status = fetch(cells[i], list);
    if (status != Status::kOk) {
      std::fill(marks_.get(), marks_.get() + words, 0);  // keep "all zero between calls"
      return status;
    }
    for (const std::uint32_t o : list) marks_[o >> 5] |= std::uint32_t{1} << (o & 31);
  }
  std::uint32_t* out = sets_.get();
  std::size_t size = 0;
  for (std::size_t w = 0; w < words; ++w) {
    for (std::uint32_t bits = marks_[w]; bits != 0; bits &= bits - 1)
      out[size++] = static_cast<std::uint32_t>(w * 32 + detail::count_trailing_zeros(bits));
    marks_[w] = 0;
  }
  result_ = out;
  size_ = size;
  return Status::kOk;
}

Status PvsDecoder::decode_delta(std::uint32_t from, std::uint32_t to) noexcept {
  clear();
  if (from >= file_->cell_count() || to >= file_->cell_count()) return Status::kOutOfRange;
  // Layout of the set storage: PVS(from) | entered | left, each at most max_pvs_size().
  // PVS(from) is copied out of the cache, whose slot fetching `to` may take.
  const std::size_t most = file_->max_pvs_size();
  if (!reserve_sets(3 * most)) return Status::kOutOfMemory;
  std::uint32_t* const before = sets_.get();
  std::uint32_t* const entered = before + most;
  std::uint32_t* const left = entered + most;
  IndexSpan list;
  Status status = fetch(from, list);
  if (status != Status::kOk) return status;
  std::copy(list.begin(), list.end(), before);
  const std::size_t n_before = list.size;
  status = fetch(to, list);
  if (status != Status::kOk) return status;
  const std::uint32_t* const after = list.data;
  const std::size_t n_after = list.size;
  // One merge of the two sorted lists.
  std::size_t i = 0, j = 0, n_entered = 0, n_left = 0;
  while (i < n_before && j < n_after) {
    if (before[i] < after[j])
      left[n_left++] = before[i++];
    else if (after[j] < before[i])
      entered[n_entered++] = after[j++];
    else
      ++i, ++j;
  }
  while (i < n_before) left[n_left++] = before[i++];
  while (j < n_after) entered[n_entered++] = after[j++];
  result_ = after;
  size_ = n_after;
  entered_ = {entered, n_entered};
  left_ = {left, n_left};
  return Status::kOk;
}

}  // namespace urbanpvs::runtime
