// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/DistributedBake.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "urbanpvs/preprocess/bake/BakeReport.hpp"

namespace urbanpvs::preprocess {
namespace {

// Worker -> rank 0: results of the last chunk (none at first), which also ask for the next one.
// Rank 0 -> worker: the next chunk's cells; an empty chunk means there is no more work.
constexpr int kTagResults = 1;
constexpr int kTagChunk = 2;

// Results: u32 threads, u64 peak resident bytes, then a journal image (header and records).
constexpr std::size_t kResultsPrefix = 12;

template <typename T>
void put(std::vector<unsigned char>& out, T v) {
  unsigned char b[sizeof(T)];
  for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
  out.insert(out.end(), b, b + sizeof(T));
}

template <typename T>
T get(const unsigned char* p) {
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(T(p[i]) << (8 * i));
  return v;
}

std::vector<unsigned char> chunk_bytes(std::span<const std::uint32_t> chunk) {
  std::vector<unsigned char> out;
  out.reserve(4 * chunk.size());
  for (std::uint32_t c : chunk) put(out, c);
  return out;
}

std::vector<std::uint32_t> chunk_of(const std::vector<unsigned char>& bytes, std::size_t cells) {
  if (bytes.size() % 4 != 0) throw std::runtime_error("rank 0 sent a malformed chunk");
  std::vector<std::uint32_t> out(bytes.size() / 4);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = get<std::uint32_t>(bytes.data() + 4 * i);
    if (out[i] >= cells) throw std::runtime_error("rank 0 sent a cell out of range");
  }
  return out;
}

void serve_rank_zero(const MpiJob& job, const BakeScene& scene, const JournalIdentity& identity,
                     const ParallelBakeOptions& options) {
  std::vector<unsigned char> journal = encode_journal_header(identity);
  for (;;) {
    std::vector<unsigned char> results;
    put<std::uint32_t>(results, options.threads);
    put<std::uint64_t>(results, peak_memory_bytes());
    results.insert(results.end(), journal.begin(), journal.end());
    job.send(0, kTagResults, results);
    const MpiJob::Message m = job.receive_from(0);
    if (m.tag != kTagChunk) throw std::runtime_error("rank 0 sent an unexpected message");
    const std::vector<std::uint32_t> chunk = chunk_of(m.bytes, scene.cell_count());
    if (chunk.empty()) return;
    journal = encode_journal_header(identity);
    std::mutex mutex;
    bake_cells(scene, chunk, options, [&](CellOutcome& o) {
      const JournalRecord record{o.cell, std::move(o.pvs), o.counters};
      const std::lock_guard lock(mutex);
      encode_journal_record(record, journal);
    });
  }
}

}  // namespace

std::size_t chunk_size(std::size_t remaining, int ranks, unsigned threads) {
  const std::size_t most = 32 * std::size_t(std::max(1u, threads));
  const std::size_t half_share = remaining / (2 * std::size_t(std::max(1, ranks)));
  return std::min(remaining, std::max<std::size_t>(1, std::min(most, half_share)));
}

std::vector<RankShare> bake_cells_across_ranks(const MpiJob& job, const BakeScene& scene,
                                               const JournalIdentity& identity,
                                               std::span<const std::uint32_t> cells,
                                               const ParallelBakeOptions& options,
                                               const std::function<void(CellOutcome&)>& finished,
                                               const std::function<void(std::size_t)>& tick) {
  if (job.rank() != 0) {
    serve_rank_zero(job, scene, identity, options);
    return {};
  }
  std::vector<RankShare> shares(static_cast<std::size_t>(job.size()));
  shares[0].threads = options.threads;
  std::size_t next = 0;  // cells[next..] are not handed out yet
  auto take = [&](unsigned threads) {
    const std::size_t n = chunk_size(cells.size() - next, job.size(), threads);
    const auto chunk = cells.subspan(next, n);
    next += n;
    return chunk;
  };
  std::atomic<std::size_t> done{0}, own{0};
  int working = job.size() - 1;  // ranks that have not been told to stop
  // One message from a worker: its results, then its next chunk (or the end).
  auto answer = [&](const MpiJob::Message& m) {
    const std::string who = "rank " + std::to_string(m.from);
    if (m.tag != kTagResults || m.bytes.size() < kResultsPrefix)
      throw std::runtime_error(who + " sent an unexpected message");
    RankShare& share = shares[static_cast<std::size_t>(m.from)];
    share.threads = get<std::uint32_t>(m.bytes.data());
    share.peak_bytes = get<std::uint64_t>(m.bytes.data() + 4);
    JournalContents contents = decode_journal(std::span(m.bytes).subspan(kResultsPrefix), identity,
                                              "the results of " + who);
    if (contents.dropped_bytes > 0) throw std::runtime_error(who + " sent damaged results");
    for (JournalRecord& r : contents.records) {
      CellOutcome outcome{r.cell, std::move(r.pvs), r.counters};
      finished(outcome);
      ++share.cells;
      ++done;
    }
    const auto chunk = take(std::max(1u, share.threads));
    job.send(m.from, kTagChunk, chunk_bytes(chunk));
    if (chunk.empty()) --working;
  };
  ParallelBakeOptions mine = options;
  mine.tick_ms = 10;  // how long a waiting rank may wait for an answer
  for (auto chunk = take(options.threads); !chunk.empty(); chunk = take(options.threads)) {
    bake_cells(
        scene, chunk, mine,
        [&](CellOutcome& o) {
          finished(o);
          ++own;
          ++done;
        },
        [&](std::size_t) {
          while (job.message_waiting()) answer(job.receive());
          if (tick) tick(done.load());
        });
  }
  while (working > 0) {
    answer(job.receive());
    if (tick) tick(done.load());
  }
  shares[0].cells = own.load();
  shares[0].peak_bytes = peak_memory_bytes();
  return shares;
}

}  // namespace urbanpvs::preprocess
