// SPDX-License-Identifier: GPL-3.0-or-later
// Times the view-cell subdivision (thesis 5.3: constrained Delaunay triangulation of free space,
// refined to the maximum cell edge) on generated cities of 1, 4 and 8 km²; 8 km² is the scale of
// the Vienna model, for which the thesis used 82,300 cells. The counters show what was built and
// how the time splits between triangulation and refinement.
#include <benchmark/benchmark.h>

#include <map>
#include <random>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/geometry/cells/CellLocator.hpp"
#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"

namespace {

using namespace urbanpvs::geometry;

// Generating and reading are not what is measured; each city is built once.
const City& city_of(int km2) {
  static std::map<int, City> cache;
  auto it = cache.find(km2);
  if (it == cache.end()) {
    urbanpvs::cities::CityParams params;
    params.size_km2 = km2;
    params.seed = 7;
    const std::string text = urbanpvs::cities::cityJsonText(urbanpvs::cities::generateCity(params));
    it = cache.emplace(km2, read_city_text(text, "generated.city.json")).first;
  }
  return it->second;
}

void BM_BuildViewCells(benchmark::State& state) {
  const City& city = city_of(static_cast<int>(state.range(0)));
  ViewCellOptions options;
  options.max_cell_edge = static_cast<double>(state.range(1));
  ViewCellMesh mesh;
  double cdt = 0, refine = 0;
  for (auto _ : state) {
    mesh = build_view_cells(city, options);
    cdt += mesh.stats.seconds_triangulation;
    refine += mesh.stats.seconds_refinement;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["buildings"] = static_cast<double>(city.objects.size());
  state.counters["cells"] = static_cast<double>(mesh.cells.size());
  state.counters["samples"] = static_cast<double>(mesh.samples.size());
  state.counters["cdt_s"] = cdt / n;
  state.counters["refine_s"] = refine / n;
}

void BM_LocateCell(benchmark::State& state) {
  const ViewCellMesh mesh = build_view_cells(city_of(8), {});
  const CellLocator locator(mesh);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> ux(mesh.bounds.min.x, mesh.bounds.max.x);
  std::uniform_real_distribution<double> uy(mesh.bounds.min.y, mesh.bounds.max.y);
  std::vector<Vec2> points(4096);
  for (Vec2& p : points) p = {ux(rng), uy(rng)};
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(locator.locate(points[i++ % points.size()]));
  state.counters["cells"] = static_cast<double>(mesh.cells.size());
}

}  // namespace

BENCHMARK(BM_BuildViewCells)
    ->ArgNames({"km2", "max_edge"})
    ->ArgsProduct({{1, 4, 8}, {18}})
    ->Args({8, 12})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocateCell);

BENCHMARK_MAIN();
