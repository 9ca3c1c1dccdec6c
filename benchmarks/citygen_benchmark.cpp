// Times generating a procedural city and writing it as CityJSON, for 1, 4 and 8 km² (8 km² is
// the scale of the Vienna model in Wonka's thesis: ~2,000 blocks). Reports the counts as
// counters so the table shows what was generated.
#include <benchmark/benchmark.h>

#include <string>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"

namespace {

void BM_GenerateAndWriteCityJson(benchmark::State& state) {
  urbanpvs::cities::CityParams params;
  params.size_km2 = static_cast<double>(state.range(0));
  params.seed = 7;
  params.roofs =
      state.range(1) != 0 ? urbanpvs::cities::RoofMode::Lod2 : urbanpvs::cities::RoofMode::Flat;
  std::size_t buildings = 0;
  std::size_t blocks = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const urbanpvs::cities::City city = urbanpvs::cities::generateCity(params);
    const std::string text = urbanpvs::cities::cityJsonText(city);
    benchmark::DoNotOptimize(text.data());
    buildings = city.buildings.size();
    blocks = city.blocks.size();
    bytes = text.size();
  }
  state.counters["buildings"] = static_cast<double>(buildings);
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
}

void BM_GenerateOnly(benchmark::State& state) {
  urbanpvs::cities::CityParams params;
  params.size_km2 = static_cast<double>(state.range(0));
  params.seed = 7;
  params.roofs = urbanpvs::cities::RoofMode::Lod2;
  for (auto _ : state) {
    const urbanpvs::cities::City city = urbanpvs::cities::generateCity(params);
    benchmark::DoNotOptimize(city.buildings.data());
  }
}

}  // namespace

BENCHMARK(BM_GenerateAndWriteCityJson)
    ->ArgNames({"km2", "lod2"})
    ->ArgsProduct({{1, 4, 8}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GenerateOnly)->ArgName("km2")->Arg(8)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
