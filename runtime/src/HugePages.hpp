// SPDX-License-Identifier: MIT
#pragma once

// Storage for the tables a random query walks (cell shapes, the point-location grid, expanded
// PVS lists): megabytes touched at random, one cache line per table per query. With 4 KiB pages
// each of those lines is also a TLB miss and a page walk, about as costly as the line itself;
// on 2 MiB pages the walks stay in cache. On the 8 km² bake a random locate went from 361-441
// to 220-241 ns p50 and locate + expanded PVS from about 1,000 to 791 ns (runtime/README.md,
// "Huge pages and a cheaper load check"). Linux gives huge pages to an aligned region advised
// with MADV_HUGEPAGE (the default "madvise" mode of transparent huge pages); elsewhere, and
// below one huge page, this is the ordinary heap.

#include <cstddef>
#include <new>
#include <vector>

#include "urbanpvs/runtime/Status.hpp"

namespace urbanpvs::runtime::detail {

/// Allocations of at least this many bytes are aligned and advised as huge pages.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
/// Smaller ones are aligned to this: whole cache lines (GridBucket, PvsExpansion records).
inline constexpr std::size_t kLargeAlignment = 64;

/// `bytes` of storage (huge pages where the platform gives them); throws std::bad_alloc.
void* allocate_large(std::size_t bytes);
/// Frees what allocate_large(bytes) returned, with the same `bytes`.
void release_large(void* p, std::size_t bytes) noexcept;

/// A standard allocator over allocate_large: vectors of it are ordinary vectors.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() noexcept = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}  // NOLINT: rebinding converts

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_large(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { release_large(p, n * sizeof(T)); }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept {
    return false;
  }
};

/// A vector whose large buffers sit on huge pages.
template <class T>
using LargeVector = std::vector<T, HugePageAllocator<T>>;

/// read_file into huge pages: PvsFile::open_file's buffer, whose PVS bytes random queries read.
Status read_file_large(const char* path, LargeVector<std::byte>& out) noexcept;

}  // namespace urbanpvs::runtime::detail
