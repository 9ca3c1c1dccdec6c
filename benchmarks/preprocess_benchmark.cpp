// SPDX-License-Identifier: GPL-3.0-or-later
// The whole urbanpvs-preprocess run (read, scene, parallel journalled cells, write) on generated
// cities of 1, 4 and 8 km² (seed 7; 8 km² is the scale of the thesis's Vienna model, ~2,000
// blocks), with every core, default settings. Prints cells, cells/s, peak memory and bytes per
// cell. Issue 7's target on a 2-core machine: 8 km² at >= 50 cells/s within 4 GB (the thesis
// needed 523 minutes for 82,300 cells: 2.6 cells/s).
//
// Each city is generated in one child process and baked in another, so each bake's peak memory
// (getrusage in the child) is its own, not the generator's or an earlier size's.
//
//   preprocess_benchmark [--sizes 1,4,8] [--threads N]
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"

namespace {

namespace fs = std::filesystem;
using namespace urbanpvs;

// Runs `job` in a child process; returns its exit status (or -1 when it died).
int in_child(const std::function<int()>& job) {
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    int rc = 1;
    try {
      rc = job();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "preprocess_benchmark: %s\n", e.what());
    }
    std::fflush(stdout);
    std::fflush(stderr);
    ::_exit(rc);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Runs urbanpvs-preprocess on generated cities and prints cells/s, peak memory "
      "and bytes per cell."};
  std::vector<double> sizes = {1, 4, 8};
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  app.add_option("--sizes", sizes, "City sizes in km2, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--threads", threads, "Worker threads [default: all cores]")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const fs::path dir =
      fs::temp_directory_path() / ("urbanpvs_preprocess_benchmark_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<std::string> rows;
  int status = 0;
  for (const double km2 : sizes) {
    char name[64];
    std::snprintf(name, sizeof name, "city_%gkm2", km2);
    const fs::path city = dir / (std::string(name) + ".city.json");
    const fs::path pvs = dir / (std::string(name) + ".pvs");
    const fs::path report = dir / (std::string(name) + ".json");
    std::fprintf(stderr, "== %g km2: generating (seed 7)\n", km2);
    if (in_child([&] {
          cities::CityParams params;
          params.size_km2 = km2;
          params.seed = 7;
          std::ofstream(city, std::ios::binary)
              << cities::cityJsonText(cities::generateCity(params));
          return 0;
        }) != 0) {
      std::fprintf(stderr, "preprocess_benchmark: cannot generate %g km2\n", km2);
      status = 1;
      continue;
    }
    std::fprintf(stderr, "== %g km2: baking on %u threads\n", km2, threads);
    const int rc = in_child([&] {
      const std::string city_arg = city.string(), out_arg = pvs.string(),
                        report_arg = report.string(), threads_arg = std::to_string(threads);
      const char* args[] = {"urbanpvs-preprocess", city_arg.c_str(),   "-o",
                            out_arg.c_str(),       "--report",         report_arg.c_str(),
                            "--threads",           threads_arg.c_str()};
      preprocess::PreprocessRequest request;
      if (const auto stop = preprocess::parse_preprocess_command_line(
              static_cast<int>(std::size(args)), args, request))
        return *stop;
      return preprocess::run_preprocess(request);
    });
    if (rc != 0) {
      std::fprintf(stderr, "preprocess_benchmark: the %g km2 bake failed (exit %d)\n", km2, rc);
      status = 1;
      continue;
    }
    std::ifstream in(report);
    const nlohmann::json r = nlohmann::json::parse(in);
    const auto& counts = r["counts"];
    const auto& seconds = r["seconds"];
    char row[256];
    std::snprintf(row, sizeof row, "%6g %8llu %8llu %9.1f %12.1f %10.1f %10.0f %9.1f %10.1f %8.1f",
                  km2, counts["objects"].get<unsigned long long>(),
                  counts["cells"].get<unsigned long long>(), seconds["scene"].get<double>(),
                  seconds["visibility"].get<double>(), r["cells_per_second"].get<double>(),
                  r["peak_memory_bytes"].get<double>() / (1024.0 * 1024.0),
                  counts["bytes_per_cell"].get<double>(), counts["pvs_mean"].get<double>(),
                  100.0 * counts["fraction_culled"].get<double>());
    rows.push_back(row);
    fs::remove(city);
    fs::remove(pvs);
    fs::remove(report);
  }
  fs::remove_all(dir);
  std::printf("threads: %u\n", threads);
  std::printf("%6s %8s %8s %9s %12s %10s %10s %9s %10s %8s\n", "km2", "objects", "cells", "scene s",
              "visibility s", "cells/s", "peak MiB", "B/cell", "mean PVS", "culled%");
  for (const std::string& row : rows) std::printf("%s\n", row.c_str());
  return status;
}
