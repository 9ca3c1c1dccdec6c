// SPDX-License-Identifier: MIT
#include "HugePages.hpp"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace urbanpvs::runtime::detail {
namespace {

/// Whether an allocation of `bytes` takes the huge-page path (decided by size alone, so
/// release_large knows without a header).
bool huge(std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  return bytes >= kHugePageBytes;
#else
  (void)bytes;
  return false;
#endif
}

}  // namespace

void* allocate_large(std::size_t bytes) {
  if (!huge(bytes)) return ::operator new (bytes, std::align_val_t{kLargeAlignment});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Whole huge pages, so the advice covers the buffer's end too; advised before anything
  // touches the memory, so its first faults already map huge pages.
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* p = nullptr;
  if (rounded < bytes || posix_memalign(&p, kHugePageBytes, rounded) != 0) throw std::bad_alloc();
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // advice only: refused, the pages stay small
  return p;
#else
  throw std::bad_alloc();  // not reached: huge() is false
#endif
}

void release_large(void* p, std::size_t bytes) noexcept {
  if (!huge(bytes)) {
    ::operator delete (p, std::align_val_t{kLargeAlignment});
    return;
  }
  std::free(p);
}

}  // namespace urbanpvs::runtime::detail
