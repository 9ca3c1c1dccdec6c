// SPDX-License-Identifier: GPL-3.0-or-later
// Brute force (one cull map over the whole city, every occluder) against the hierarchical test
// of thesis 5.6 (growing maps, horizon, occluded occluders, early break) on generated cities.
// Both run on the same evenly spread cells; the table shows cells per second for each, the
// speed-up, and how the two PVSs compare cell by cell (the hierarchical one must be a superset,
// at most 2% larger on average). Hierarchical counters show where its time goes.
//
//   hierarchical_benchmark [--sizes 1,4,8] [--cells N] [--brute-cells N] [--seed S] [--max-map PX]
//                          [--initial-map PX]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"

namespace {

using namespace urbanpvs;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::vector<std::uint32_t> spread(std::size_t total, std::size_t n) {
  std::vector<std::uint32_t> out;
  n = std::min(n, total);
  for (std::size_t k = 0; k < n; ++k) out.push_back(static_cast<std::uint32_t>(k * total / n));
  return out;
}

std::vector<double> parse_list(const char* s) {
  std::vector<double> out;
  for (const char* p = s; *p;) {
    char* end = nullptr;
    out.push_back(std::strtod(p, &end));
    p = *end == ',' ? end + 1 : end;
    if (end == p && *p) break;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes{1, 4, 8};
  std::size_t cells = 400, brute_cells = 20;
  std::uint64_t seed = 7;
  int max_map = preprocess::BakeOptions{}.max_map;
  int initial_map = preprocess::BakeOptions{}.initial_map;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes"))
      sizes = parse_list(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--cells"))
      cells = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--brute-cells"))
      brute_cells = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--seed"))
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--max-map"))
      max_map = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--initial-map"))
      initial_map = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr,
                   "usage: %s [--sizes 1,4,8] [--cells N] [--brute-cells N] [--seed S] [--max-map "
                   "PX] [--initial-map PX]\n",
                   argv[0]);
      return 2;
    }
  }
  std::printf("%6s %7s %8s %9s %9s %8s %9s %9s %8s %8s %7s %7s %8s %8s\n", "km2", "objects",
              "cells", "brute/s", "hier/s", "speedup", "compared", "notsuper", "extra%", "meanPVS",
              "maps", "early%", "rend/c", "maxmap");
  for (double km2 : sizes) {
    cities::CityParams p;
    p.size_km2 = km2;
    p.seed = seed;
    const geometry::City city = geometry::read_city_text(
        cities::cityJsonText(cities::generateCity(p)), "generated.city.json");
    preprocess::BakeOptions options;
    options.max_map = max_map;
    options.initial_map = initial_map;
    const preprocess::BakeScene hier_scene(city, options);
    options.method = preprocess::Method::BruteForce;
    const preprocess::BakeScene brute_scene(city, options);
    preprocess::CellVisibility hier(hier_scene), brute(brute_scene);

    const std::vector<std::uint32_t> timed = spread(hier_scene.cell_count(), cells);
    preprocess::CellCounters hc;
    std::vector<std::vector<std::uint32_t>> hier_pvs;
    const auto t0 = Clock::now();
    for (std::uint32_t c : timed) hier_pvs.push_back(hier.pvs(c, &hc));
    const double hier_rate = double(timed.size()) / seconds_since(t0);

    // Brute force on every (timed.size() / brute_cells)-th of the same cells.
    const std::size_t stride =
        std::max<std::size_t>(1, timed.size() / std::max<std::size_t>(1, brute_cells));
    std::size_t compared = 0, not_superset = 0;
    double extra = 0, brute_total = 0;
    const auto t1 = Clock::now();
    for (std::size_t k = 0; k < timed.size(); k += stride) {
      const std::vector<std::uint32_t> b = brute.pvs(timed[k]);
      const std::vector<std::uint32_t>& h = hier_pvs[k];
      ++compared;
      if (!std::includes(h.begin(), h.end(), b.begin(), b.end())) {
        ++not_superset;
        std::vector<std::uint32_t> missing;
        std::set_difference(b.begin(), b.end(), h.begin(), h.end(), std::back_inserter(missing));
        for (std::uint32_t o : missing)
          std::printf("       not a superset: cell %u misses object %u\n", timed[k], o);
      }
      extra += double(h.size()) - double(b.size());
      brute_total += double(b.size());
    }
    const double brute_rate = double(compared) / seconds_since(t1);
    double pvs_total = 0;
    for (const auto& h : hier_pvs) pvs_total += double(h.size());
    std::printf("%6.1f %7zu %8zu %9.2f %9.1f %8.1f %9zu %9zu %8.3f %8.1f %7.2f %7.1f %8.1f %8llu\n",
                km2, city.objects.size(), hier_scene.cell_count(), brute_rate, hier_rate,
                hier_rate / brute_rate, compared, not_superset,
                brute_total > 0 ? 100.0 * extra / brute_total : 0.0,
                pvs_total / double(timed.size()), double(hc.maps) / double(hc.cells),
                100.0 * double(hc.early_breaks) / double(hc.cells),
                double(hc.occluders_rendered) / double(hc.cells),
                static_cast<unsigned long long>(hc.largest_map));
    std::printf(
        "       per cell: occluders considered %.1f occluded %.1f behind-horizon %.1f; "
        "objects in map %.1f; nodes rejected %.1f; shadows %.0f; "
        "pixels %.0f; far field: objects %.1f, occluders added %.1f (all samples), sight lines "
        "%.1f\n",
        double(hc.occluders_considered) / double(hc.cells),
        double(hc.occluders_occluded) / double(hc.cells),
        double(hc.occluders_behind_horizon) / double(hc.cells),
        double(hc.objects_in_map) / double(hc.cells),
        double(hc.nodes_behind_horizon) / double(hc.cells), double(hc.shadows) / double(hc.cells),
        double(hc.pixels_written) / double(hc.cells),
        double(hc.objects_far_field) / double(hc.cells),
        double(hc.occluders_far_field) / double(hc.cells),
        double(hc.sight_lines) / double(hc.cells));
    std::fflush(stdout);
  }
  return 0;
}
