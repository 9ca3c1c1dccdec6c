// SPDX-License-Identifier: MIT
// Runtime benchmark: what a simulator pays per frame for "what can I see from here?".
//
//   runtime_benchmark                      all benchmarks
//   runtime_benchmark --benchmark_filter=Query
//   runtime_benchmark --files A.pvs [B.pvs ...]   real bakes: one table row per format
//                                                 (RuntimeFileTable.cpp)
//
// Counters: query_p50_ns / query_p90_ns / query_p99_ns (locate + iterate the PVS, timed one by
// one, timer overhead subtracted), bytes_per_cell (pvs section / cells), ratio_vs_plain (pvs
// section / 4 bytes per visible object), mean_pvs and neighbour_overlap of the synthetic city.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <string_view>

#include "RuntimeFileTable.hpp"
#include "SyntheticCity.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

using urbanpvs::runtime::EncodeOptions;
using urbanpvs::runtime::PvsBake;
using urbanpvs::runtime::PvsDecoder;
using urbanpvs::runtime::PvsFile;

const PvsBake& city() {
  static const PvsBake bake = urbanpvs::test::synthetic_city({});
  return bake;
}

/// A loaded file per encoding configuration (max chain, threshold × 100).
struct Loaded {
  std::vector<std::byte> bytes;
  PvsFile file;
  std::uint64_t pvs_bytes = 0;
};

Loaded& loaded(std::uint32_t chain, int threshold_percent) {
  static std::map<std::pair<std::uint32_t, int>, Loaded> cache;
  Loaded& l = cache[{chain, threshold_percent}];
  if (!l.file.is_open()) {
    EncodeOptions options;
    options.max_diff_chain = chain;
    options.diff_threshold = threshold_percent / 100.0;
    l.bytes = urbanpvs::runtime::encode(city(), options);
    if (PvsFile::open(l.bytes.data(), l.bytes.size(), l.file) != urbanpvs::runtime::Status::kOk) {
      std::abort();
    }
    for (std::size_t i = 0; i < l.file.section_count(); ++i) {
      const auto s = l.file.section(i);
      if (s.id == static_cast<std::uint32_t>(urbanpvs::runtime::format::SectionId::kPvs)) {
        l.pvs_bytes = s.length;
      }
    }
  }
  return l;
}

/// Random query points over the city at eye height, in the local frame: every query touches
/// memory no other recent query touched (the cache-cold worst case).
std::vector<std::array<double, 3>> query_points(std::size_t n) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> pos(0, 3000), eye(1.5, 2.0);
  std::vector<std::array<double, 3>> points(n);
  for (auto& p : points) p = {pos(rng), pos(rng), eye(rng)};
  return points;
}

/// 200 agents walking through the city, 2 m per query each, turning now and then, queried
/// round-robin: what a simulator does every frame.
std::vector<std::array<double, 3>> walk_points(std::size_t n) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> pos(100, 2900), turn(-0.3, 0.3), angle(0, 6.2831853);
  constexpr std::size_t kAgents = 200;
  std::vector<std::array<double, 3>> agents(kAgents);
  for (auto& a : agents) a = {pos(rng), pos(rng), angle(rng)};
  std::vector<std::array<double, 3>> points(n);
  for (std::size_t i = 0; i < n; ++i) {
    auto& a = agents[i % kAgents];
    a[2] += turn(rng);
    a[0] += 2 * std::cos(a[2]);
    a[1] += 2 * std::sin(a[2]);
    if (a[0] < 0 || a[0] > 3000 || a[1] < 0 || a[1] > 3000) a[2] += 3.14159265;  // bounce
    a[0] = std::clamp(a[0], 0.0, 3000.0);
    a[1] = std::clamp(a[1], 0.0, 3000.0);
    points[i] = {a[0], a[1], 1.75};
  }
  return points;
}

void add_size_counters(benchmark::State& state, const Loaded& l) {
  const double cells = l.file.cell_count();
  const double entries = static_cast<double>(l.file.total_pvs_entries());
  state.counters["bytes_per_cell"] = static_cast<double>(l.pvs_bytes) / cells;
  state.counters["plain_bytes_per_cell"] = 4 * entries / cells;
  state.counters["ratio_vs_plain"] = static_cast<double>(l.pvs_bytes) / (4 * entries);
  state.counters["file_MB"] = static_cast<double>(l.bytes.size()) / 1e6;
}

/// One query: locate, then touch every visible object index.
inline std::uint64_t query(const PvsFile& file, PvsDecoder& decoder,
                           const std::array<double, 3>& p) {
  const std::uint32_t cell = file.locate(p[0], p[1], p[2]);
  if (cell == urbanpvs::runtime::kNoCell ||
      decoder.decode(cell) != urbanpvs::runtime::Status::kOk) {
    return 0;
  }
  std::uint64_t sum = 0;
  for (std::uint32_t object : decoder) sum += object;
  return sum;
}

/// Per-query latency percentiles, each query timed on its own. Args: max diff chain, diff
/// threshold in percent, pattern (0 = random points, 1 = walking agents).
void BM_Query(benchmark::State& state) {
  const Loaded& l =
      loaded(static_cast<std::uint32_t>(state.range(0)), static_cast<int>(state.range(1)));
  PvsDecoder decoder(l.file);
  const auto points = state.range(2) == 0 ? query_points(20000) : walk_points(20000);
  using clock = std::chrono::steady_clock;
  std::vector<double> ns;
  ns.reserve(points.size());
  const double overhead = urbanpvs::bench::timer_overhead_ns();
  std::uint64_t sink = 0;
  for (auto _ : state) {
    ns.clear();
    for (const auto& p : points) {
      const auto t0 = clock::now();
      sink += query(l.file, decoder, p);
      const auto t1 = clock::now();
      ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() - overhead);
    }
  }
  benchmark::DoNotOptimize(sink);
  std::sort(ns.begin(), ns.end());
  state.counters["query_p50_ns"] = ns[ns.size() / 2];
  state.counters["query_p90_ns"] = ns[ns.size() * 9 / 10];
  state.counters["query_p99_ns"] = ns[ns.size() * 99 / 100];
  add_size_counters(state, l);
}
BENCHMARK(BM_Query)
    ->ArgNames({"chain", "threshold%", "walk"})
    ->Args({1, 30, 0})  // the default encoding
    ->Args({1, 30, 1})
    ->Args({0, 100, 0})  // full lists only
    ->Args({0, 100, 1})
    ->Args({1, 70, 0})
    ->Args({1, 70, 1})
    ->Args({2, 30, 0})
    ->Args({2, 30, 1})
    ->Args({4, 30, 0})
    ->Args({4, 30, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

/// Throughput: queries back to back (mean time per query = time / items).
void BM_QueryThroughput(benchmark::State& state) {
  const Loaded& l = loaded(1, 30);
  PvsDecoder decoder(l.file);
  const auto points = query_points(4096);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(query(l.file, decoder, points[i++ & 4095]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QueryThroughput);

void BM_LocateOnly(benchmark::State& state) {
  const Loaded& l = loaded(1, 30);
  const auto points = query_points(4096);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& p = points[i++ & 4095];
    benchmark::DoNotOptimize(l.file.locate(p[0], p[1], p[2]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LocateOnly);

void BM_IsVisible(benchmark::State& state) {
  const Loaded& l = loaded(1, 30);
  std::mt19937 rng(7);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(4096);
  for (auto& p : pairs) p = {rng() % l.file.cell_count(), rng() % l.file.object_count()};
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& p = pairs[i++ & 4095];
    benchmark::DoNotOptimize(l.file.is_visible(p.first, p.second));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IsVisible);

void BM_Load(benchmark::State& state) {
  const Loaded& l = loaded(1, 30);
  for (auto _ : state) {
    PvsFile file;
    benchmark::DoNotOptimize(PvsFile::open(l.bytes.data(), l.bytes.size(), file));
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(l.bytes.size()));
}
BENCHMARK(BM_Load)->Unit(benchmark::kMillisecond);

void BM_Encode(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(urbanpvs::runtime::encode(city()));
}
BENCHMARK(BM_Encode)->Unit(benchmark::kMillisecond)->Iterations(1);

/// Statistics of the synthetic city itself: is it as coherent as claimed?
void BM_CityStatistics(benchmark::State& state) {
  const PvsBake& bake = city();
  double overlap_sum = 0, size_sum = 0;
  std::size_t pairs = 0, min_size = SIZE_MAX, max_size = 0;
  for (auto _ : state) {
    for (std::size_t c = 0; c < bake.cells.size(); ++c) {
      const auto& a = bake.cells[c].pvs;
      size_sum += static_cast<double>(a.size());
      min_size = std::min(min_size, a.size());
      max_size = std::max(max_size, a.size());
      for (std::uint32_t nb : bake.cells[c].neighbours) {
        if (nb == urbanpvs::runtime::kNoCell) continue;
        const auto& b = bake.cells[nb].pvs;
        std::vector<std::uint32_t> common;
        std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
        overlap_sum +=
            static_cast<double>(common.size()) / static_cast<double>(std::max(a.size(), b.size()));
        ++pairs;
      }
    }
  }
  state.counters["cells"] = static_cast<double>(bake.cells.size());
  state.counters["objects"] = static_cast<double>(bake.objects.size());
  state.counters["mean_pvs"] = size_sum / static_cast<double>(bake.cells.size());
  state.counters["min_pvs"] = static_cast<double>(min_size);
  state.counters["max_pvs"] = static_cast<double>(max_size);
  state.counters["neighbour_overlap"] = overlap_sum / static_cast<double>(pairs);
}
BENCHMARK(BM_CityStatistics)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string_view(argv[1]) == "--files") {
    return urbanpvs::bench::run_file_table(argc - 2, argv + 2);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
