// SPDX-License-Identifier: MIT
#pragma once

#include <cstddef>

namespace urbanpvs::bench {

/// Nanoseconds per load of a chain of dependent loads through `bytes` of memory in random order
/// (one 64-byte line per step, huge pages where the system gives them, as the runtime's tables
/// get): the time a lookup pays for each cache miss that waits for the one before. A table of
/// `runtime_benchmark --files` prints it beside the random-query latencies, whose floor is the
/// number of such misses in a row times this.
double memory_latency_ns(std::size_t bytes);

}  // namespace urbanpvs::bench
