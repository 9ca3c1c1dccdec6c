// SPDX-License-Identifier: MIT
#include "MemoryLatency.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace urbanpvs::bench {

double memory_latency_ns(std::size_t bytes) {
  struct Line {
    const Line* next;
    unsigned char pad[56];
  };
  const std::size_t lines = std::max<std::size_t>(bytes / sizeof(Line), 2);
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  const std::size_t size = (lines * sizeof(Line) + kHugePage - 1) / kHugePage * kHugePage;
  void* memory = std::aligned_alloc(kHugePage, size);
  if (memory == nullptr) return 0;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(memory, size, MADV_HUGEPAGE);
#endif
  auto* line = static_cast<Line*>(memory);
  // One cycle through every line in random order: no prefetcher can guess the next.
  std::vector<std::size_t> order(lines);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), std::mt19937_64(7));
  for (std::size_t i = 0; i < lines; ++i) line[order[i]].next = &line[order[(i + 1) % lines]];
  const Line* at = &line[order[0]];
  for (std::size_t i = 0; i < lines; ++i) at = at->next;  // touch every page once
  constexpr std::size_t kSteps = 4'000'000;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < kSteps; ++i) at = at->next;
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  // The chain's end decides what is printed, so the loop cannot be dropped.
  const double result = at != nullptr ? ns / kSteps : 0;
  std::free(memory);
  return result;
}

}  // namespace urbanpvs::bench
