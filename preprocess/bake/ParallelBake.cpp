// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/ParallelBake.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "urbanpvs/preprocess/bake/CellOrder.hpp"

namespace urbanpvs::preprocess {
namespace {

// Hands out chunks of the cell list. Chunks shrink towards the end (a quarter of a thread's
// share of what is left), so the last chunks finish close together instead of one thread
// working alone through 64 slow cells.
class ChunkQueue {
 public:
  ChunkQueue(std::size_t size, unsigned threads, std::size_t max_chunk)
      : size_(size), threads_(threads), max_chunk_(std::max<std::size_t>(1, max_chunk)) {}

  /// False when no cell is left.
  bool take(std::size_t& begin, std::size_t& end) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (next_ == size_) return false;
    const std::size_t left = size_ - next_;
    const std::size_t chunk = std::clamp<std::size_t>(left / (4 * threads_), 1, max_chunk_);
    begin = next_;
    end = next_ + chunk;
    next_ = end;
    return true;
  }

 private:
  std::mutex mutex_;
  std::size_t next_ = 0;
  const std::size_t size_;
  const std::size_t threads_;
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

  auto work = [&] {
    try {
      CellVisibility visibility(scene);
      std::size_t begin = 0, end = 0;
      while (!stop.load(std::memory_order_relaxed) && queue.take(begin, end)) {
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
    for (unsigned t = 0; t < threads; ++t) workers.emplace_back(work);
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
