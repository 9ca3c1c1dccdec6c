// SPDX-License-Identifier: GPL-3.0-or-later
// One typical view cell of a generated 1 km² city: the cell cull map over the whole city with
// every occluder (the brute-force form), per backend. Counters: samples, shadows rendered,
// pixels written, ms per sample.
#include <benchmark/benchmark.h>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"
#include "urbanpvs/preprocess/visibility/OsMesaCullMapRenderer.hpp"

namespace {

using namespace urbanpvs;

struct Scene {
  geometry::City city;
  std::vector<geometry::Occluder> occluders;
  std::vector<preprocess::Vec3> samples;
  preprocess::CullMapGrid grid;
};

const Scene& scene() {
  static const Scene s = [] {
    Scene out;
    cities::CityParams p;
    p.size_km2 = 1;
    p.seed = 1;
    out.city = geometry::read_city_text(cities::cityJsonText(cities::generateCity(p)), "1km2");
    out.occluders = geometry::shrink_blocks(geometry::build_blocks(out.city.objects, {}), 1.0);
    const geometry::ViewCellMesh mesh = geometry::build_view_cells(out.city, {});
    // The cell nearest the city centre.
    const geometry::Box2 b = out.city.bounds().xy;
    const geometry::Vec2 c{0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y)};
    std::size_t best = 0;
    double best_d = 1e300;
    for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
      const auto& t = mesh.cells[i].corner;
      const double d =
          std::hypot((t[0].x + t[1].x + t[2].x) / 3 - c.x, (t[0].y + t[1].y + t[2].y) / 3 - c.y);
      if (d < best_d) best = i, best_d = d;
    }
    for (std::uint32_t e : mesh.cells[best].edge)
      for (const geometry::Vec3& q : mesh.samples_of(mesh.edges[e]))
        out.samples.push_back({q.x, q.y, q.z});
    out.grid = preprocess::CullMapGrid::covering(b.grown(10), 1.39);
    return out;
  }();
  return s;
}

void report(benchmark::State& state, const preprocess::CullMapStats& st, std::size_t cells) {
  const Scene& s = scene();
  state.counters["samples"] = double(s.samples.size());
  state.counters["shadows/cell"] = double(st.shadows) / double(cells);
  state.counters["pixels/cell"] = double(st.pixels_written) / double(cells);
  state.counters["map_px"] = double(s.grid.width) * s.grid.height;
  state.counters["ms/sample"] =
      benchmark::Counter(double(cells * s.samples.size()) / 1000.0,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_CpuCellCullMap(benchmark::State& state) {
  const Scene& s = scene();
  preprocess::CullMapStats st;
  std::size_t cells = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(preprocess::cell_cull_map(s.grid, s.samples, s.occluders, &st));
    ++cells;
  }
  report(state, st, cells);
}

void BM_OsMesaCellCullMap(benchmark::State& state) {
  const Scene& s = scene();
  preprocess::OsMesaCullMapRenderer gl;
  preprocess::CullMapStats st;
  std::size_t cells = 0;
  const geometry::Box3 b = s.city.bounds();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        gl.cell_cull_map(s.grid, s.samples, s.occluders, b.zmin - 1, b.zmax + 1000, &st));
    ++cells;
  }
  report(state, st, cells);
}

}  // namespace

BENCHMARK(BM_CpuCellCullMap)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK(BM_OsMesaCellCullMap)->Unit(benchmark::kMillisecond)->MinTime(2);
BENCHMARK_MAIN();
