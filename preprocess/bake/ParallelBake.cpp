// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/ParallelBake.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "urbanpvs/preprocess/bake/CellOrder.hpp"

namespace urbanpvs::preprocess {
namespace {

// Hands out chunks of the cell list, which runs along the Hilbert curve. Each thread owns one
// stretch of it and takes its chunks from the front, so that it walks from neighbour to
// neighbour and its FarField finds their shared samples kept; threads that took chunks in turn
// from one shared counter each saw every other chunk, and lost the samples across its ends.
// A thread whose stretch is done takes the back half of the longest one left.
class ChunkQueue {
 public:
  ChunkQueue(std::size_t size, unsigned threads, std::size_t max_chunk)
      : max_chunk_(std::max<std::size_t>(1, max_chunk)) {
    for (unsigned t = 0; t < threads; ++t)
      stretch_.push_back({size * t / threads, size * (t + 1) / threads});
  }

  /// Thread t's next chunk; false when no cell is left.
  bool take(unsigned t, std::size_t& begin, std::size_t& end) {
    const std::lock_guard<std::mutex> lock(mutex_);
    Stretch& own = stretch_[t];
    if (own.begin == own.end) {
      auto longest = std::max_element(
          stretch_.begin(), stretch_.end(),
          [](const Stretch& a, const Stretch& b) { return a.end - a.begin < b.end - b.begin; });
      if (longest->begin == longest->end) return false;
      const std::size_t middle = longest->begin + (longest->end - longest->begin) / 2;
      own = {middle, longest->end};
      longest->end = middle;
    }
    // A quarter of what the stretch has left, so that near the end the chunk being worked on
    // (which no other thread can take) is short, and the last cells finish close together.
    begin = own.begin;
    end = own.begin + std::clamp<std::size_t>((own.end - own.begin) / 4, 1, max_chunk_);
    own.begin = end;
    return true;
  }

 private:
  struct Stretch {
    std::size_t begin, end;
  };
  std::mutex mutex_;
  std::vector<Stretch> stretch_;  ///< per thread: the cells it has still to take
  const std::size_t max_chunk_;
};

}  // namespace

void bake_cells(const BakeScene& scene, std::span<const std::uint32_t> cells,
                const ParallelBakeOptions& options,
                const std::function<void(CellOutcome&)>& finished,
                const std::function<void(std::size_t)>& tick) {
  const unsigned threads = std::max(1u, options.threads);
  // Neighbours one after another: each thread's FarField finds their shared samples kept.
  const std::vector<std::uint32_t> order = along_hilbert_curve(scene.mesh(), cells);
  ChunkQueue queue(order.size(), threads, options.max_chunk);
  std::atomic<std::size_t> done{0};
  std::atomic<bool> stop{false};
  std::mutex state_mutex;
  std::condition_variable state_changed;
  std::exception_ptr failure;
  unsigned running = threads;

  auto work = [&](unsigned t) {
    try {
      CellVisibility visibility(scene);
      std::size_t begin = 0, end = 0;
      while (!stop.load(std::memory_order_relaxed) && queue.take(t, begin, end)) {
        for (std::size_t i = begin; i < end && !stop.load(std::memory_order_relaxed); ++i) {
          CellOutcome outcome;
          outcome.cell = order[i];
          outcome.pvs = visibility.pvs(outcome.cell, &outcome.counters);
          finished(outcome);
          done.fetch_add(1, std::memory_order_relaxed);
        }
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(state_mutex);
      if (!failure) failure = std::current_exception();
      stop.store(true);
    }
    const std::lock_guard<std::mutex> lock(state_mutex);
    --running;
    state_changed.notify_all();
  };

  std::vector<std::thread> workers;
  workers.reserve(threads);
  try {
    for (unsigned t = 0; t < threads; ++t) workers.emplace_back(work, t);
  } catch (...) {
    // Could not start a thread: let the started ones stop, then report.
    stop.store(true);
    {
      const std::lock_guard<std::mutex> lock(state_mutex);
      running -= threads - static_cast<unsigned>(workers.size());
    }
    for (std::thread& w : workers) w.join();
    throw;
  }
  {
    std::unique_lock<std::mutex> lock(state_mutex);
    while (running > 0) {
      state_changed.wait_for(lock, std::chrono::milliseconds(std::max(1, options.tick_ms)));
      if (tick && running > 0 && !stop.load()) {
        lock.unlock();
        try {
          tick(done.load(std::memory_order_relaxed));
        } catch (...) {
          // The workers must still be joined before anything leaves this function.
          lock.lock();
          if (!failure) failure = std::current_exception();
          stop.store(true);
          continue;
        }
        lock.lock();
      }
    }
  }
  for (std::thread& w : workers) w.join();
  if (failure) std::rethrow_exception(failure);
  if (tick) tick(done.load());
}

}  // namespace urbanpvs::preprocess
