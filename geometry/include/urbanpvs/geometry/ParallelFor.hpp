// SPDX-License-Identifier: GPL-3.0-or-later
// Independent pieces of work shared out to threads: the roof faces' blocks (RoofPlaneOccluders)
// and urbanpvs-explain's cells and runs. Results go to per-index slots, so they do not depend on
// the number of threads; neither does the error, which is the lowest failing index's.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace urbanpvs::geometry {

/// Calls work(thread, i) for every i < n on `threads` threads (the calling one included, thread
/// 0). When calls throw, the exception of the lowest such i is rethrown once all have stopped:
/// indices are handed out in order, so every lower one was already taken and runs to its end,
/// and no higher one is started.
inline void parallel_for(std::size_t n, unsigned threads,
                         const std::function<void(unsigned, std::size_t)>& work) {
  std::atomic<std::size_t> next{0};
  std::size_t failed_at = n;
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto run = [&](unsigned thread) {
    for (std::size_t i; (i = next++) < n;) {
      try {
        work(thread, i);
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        if (i < failed_at) {
          failed_at = i;
          failure = std::current_exception();
        }
        next = n;
      }
    }
  };
  std::vector<std::thread> pool;
  const std::size_t count = threads < n ? threads : n;
  for (unsigned t = 1; t < count; ++t) pool.emplace_back(run, t);
  run(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace urbanpvs::geometry
