// SPDX-License-Identifier: GPL-3.0-or-later
// The whole urbanpvs-preprocess run (read, scene, parallel journalled cells, write) with the
// default settings, on generated cities of 1, 4 and 8 km² (seed 7; 8 km² is the scale of the
// thesis's Vienna model, ~2,000 blocks) and on every real city of ../shared/cities (issue 13):
// the CityJSON and GeoJSON files as they are, the OSM files the way benchmarks/osm_cities.sh
// bakes them (Monaco and Andorra on their SRTM tiles, Andorra and Liechtenstein on their
// streets). A city that is absent is skipped with a line that says so.
//
// Prints per city: objects, cells, cells/s (wall, all threads), thread-milliseconds per cell
// (what one core spends on a cell: comparable across thread counts and city sizes), the same
// per entry of the mean PVS (the sweeps' work follows what a cell sees: this is what stays
// level from 1 to 8 km² when time per cell does not, README "urbanpvs-preprocess"), peak MiB,
// mean PVS, culled share, and the PVS change against an earlier run (--compare DIR: the .pvs
// files a run with --save DIR left, read with the runtime library; per cell, the entries added
// and removed). --tool runs another urbanpvs-preprocess binary instead of this build's (an
// earlier commit's, for the "before" column), with the same arguments. --bake-options adds
// options to every bake (an experimental setting, other cells), each replacing the city's own
// option of that name: e.g. Andorra la Vella's square on its DEM with the terrain as sloped
// squares (README, "Terrain as an occluder"):
//
//   preprocess_benchmark --sizes 0 --only andorra --bake-options="--terrain-planes 64
//     --cells benchmarks/regions/andorra_la_vella.geojson"
//
// Each city is generated in one child process and baked in another, so each bake's peak memory
// is its own, not the generator's or an earlier city's.
//
//   preprocess_benchmark [--sizes 1,4,8] [--cities DIR] [--only TEXT] [--threads N]
//                        [--tool PATH] [--save DIR] [--compare DIR] [--bake-options="..."]
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

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

// One bake: an input with its options, or a generated city (km2 > 0).
struct BenchCity {
  std::string name;
  fs::path input;
  std::vector<std::string> options;
  double km2 = 0;
};

// The real cities of `dir` as the bake defaults take them; the OSM files as osm_cities.sh.
std::vector<BenchCity> real_cities(const fs::path& dir) {
  std::vector<BenchCity> out;
  if (dir.empty()) return out;
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    const std::string n = f.filename().string();
    if (n.ends_with(".city.json") || n.ends_with(".geojson")) out.push_back({n, f, {}, 0});
  }
  struct Osm {
    const char *file, *cells, *dem;
  };
  for (const Osm& o : {Osm{"Helsinki.osm.pbf", "everywhere", nullptr},
                       Osm{"monaco-2021.osm.pbf", "everywhere", "dem/N43E007.hgt"},
                       Osm{"andorra-2013.osm.pbf", "streets", "dem/N42E001.hgt"},
                       Osm{"liechtenstein-2013-08-03.osm.pbf", "streets", nullptr}}) {
    BenchCity c{o.file, dir / o.file, {"--cells", o.cells}, 0};
    if (o.dem) {
      c.options.insert(c.options.end(), {"--terrain", (dir / o.dem).string()});
      c.name += " +dem";
    }
    if (std::string(o.cells) == "streets") c.name += " streets";
    if (!fs::exists(c.input) || (o.dem && !fs::exists(dir / o.dem))) {
      std::fprintf(stderr, "SKIP: %s (or its DEM) is absent\n", c.input.string().c_str());
      continue;
    }
    out.push_back(std::move(c));
  }
  return out;
}

// A file name for a city's saved PVS.
std::string file_stem(const std::string& name) {
  std::string s;
  for (char ch : name) s += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return s;
}

// The PVS of `now` against `before`, cell by cell: "same", or the entries' change in per cent
// with the cells that differ and the entries removed; "-" without a file to compare with.
std::string pvs_change(const fs::path& now, const fs::path& before) {
  if (before.empty() || !fs::exists(before)) return "-";
  runtime::PvsFile a, b;
  if (runtime::PvsFile::open_file(now.string().c_str(), a) != runtime::Status::kOk ||
      runtime::PvsFile::open_file(before.string().c_str(), b) != runtime::Status::kOk)
    return "unreadable";
  if (a.cell_count() != b.cell_count() || a.object_count() != b.object_count())
    return "other cells";
  std::vector<std::uint32_t> x(a.decode_buffer_size()), y(b.decode_buffer_size()), only;
  std::size_t differ = 0, removed = 0;
  for (std::uint32_t c = 0; c < a.cell_count(); ++c) {
    std::size_t nx = 0, ny = 0;
    if (a.decode_pvs(c, x.data(), x.size(), nx) != runtime::Status::kOk ||
        b.decode_pvs(c, y.data(), y.size(), ny) != runtime::Status::kOk)
      return "unreadable";
    if (std::equal(x.begin(), x.begin() + nx, y.begin(), y.begin() + ny)) continue;
    ++differ;
    only.clear();
    std::set_difference(y.begin(), y.begin() + ny, x.begin(), x.begin() + nx,
                        std::back_inserter(only));
    removed += only.size();
  }
  if (differ == 0) return "same";
  char text[96];
  const double change = 100.0 * (double(a.total_pvs_entries()) - double(b.total_pvs_entries())) /
                        std::max(1.0, double(b.total_pvs_entries()));
  std::snprintf(text, sizeof text, "%+.2f%% (%zu cells, %zu removed)", change, differ, removed);
  return text;
}

// Appends `extra` (options, each with its value when the next item does not start with "--")
// to `args`, dropping an option of the same name that `args` already has, with its value.
void with_options(std::vector<std::string>& args, const std::vector<std::string>& extra) {
  auto has_value = [](const std::vector<std::string>& v, std::size_t i) {
    return i + 1 < v.size() && !v[i + 1].starts_with("--");
  };
  for (std::size_t i = 0; i < extra.size(); ++i) {
    if (!extra[i].starts_with("--")) continue;
    for (std::size_t k = 0; k < args.size(); ++k)
      if (args[k] == extra[i]) {
        args.erase(args.begin() + static_cast<std::ptrdiff_t>(k),
                   args.begin() + static_cast<std::ptrdiff_t>(k + (has_value(args, k) ? 2 : 1)));
        break;
      }
  }
  args.insert(args.end(), extra.begin(), extra.end());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Runs urbanpvs-preprocess on generated and real cities and prints cells/s, time per cell, "
      "peak memory, mean PVS and the PVS change against an earlier run."};
  std::vector<double> sizes = {1, 4, 8};
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  fs::path cities_dir = URBANPVS_SHARED_CITIES, tool, save, compare;
  std::string only;
  app.add_option("--sizes", sizes, "Generated city sizes in km2, comma-separated (0: none)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--cities", cities_dir, "Directory of real cities (empty: none)")
      ->capture_default_str();
  app.add_option("--only", only, "Only the cities whose name contains this text");
  app.add_option("--threads", threads, "Worker threads [default: all cores]")
      ->capture_default_str();
  app.add_option("--tool", tool, "Another urbanpvs-preprocess binary to run instead of this build");
  app.add_option("--save", save, "Keep each city's .pvs in this directory");
  app.add_option("--compare", compare, "Compare each PVS with the .pvs of the same city here");
  std::string bake_options;
  app.add_option(
      "--bake-options", bake_options,
      "Options for every bake, after '=' and in quotes (--bake-options=\"--terrain-planes "
      "64\"); each replaces a city's own option of its name");
  CLI11_PARSE(app, argc, argv);
  std::vector<std::string> extra;
  for (std::istringstream words(bake_options); !words.eof();)
    if (std::string w; words >> w) extra.push_back(w);

  const fs::path dir =
      fs::temp_directory_path() / ("urbanpvs_preprocess_benchmark_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  if (!save.empty()) fs::create_directories(save);
  std::vector<BenchCity> list;
  for (const double km2 : sizes) {
    if (!(km2 > 0)) continue;
    char name[64];
    std::snprintf(name, sizeof name, "generated %g km2", km2);
    list.push_back({name, dir / (file_stem(name) + ".city.json"), {}, km2});
  }
  for (BenchCity& c : real_cities(cities_dir)) list.push_back(std::move(c));
  std::vector<std::string> rows;
  int status = 0;
  for (const BenchCity& city : list) {
    if (!only.empty() && city.name.find(only) == std::string::npos) continue;
    const std::string stem = file_stem(city.name);
    const fs::path pvs = dir / (stem + ".pvs"), report = dir / (stem + ".json");
    if (city.km2 > 0) {
      std::fprintf(stderr, "== %s: generating (seed 7)\n", city.name.c_str());
      if (in_child([&] {
            cities::CityParams params;
            params.size_km2 = city.km2;
            params.seed = 7;
            std::ofstream(city.input, std::ios::binary)
                << cities::cityJsonText(cities::generateCity(params));
            return 0;
          }) != 0) {
        std::fprintf(stderr, "preprocess_benchmark: cannot generate %s\n", city.name.c_str());
        status = 1;
        continue;
      }
    }
    std::fprintf(stderr, "== %s: baking on %u threads\n", city.name.c_str(), threads);
    std::vector<std::string> args = {tool.empty() ? "urbanpvs-preprocess" : tool.string(),
                                     city.input.string(),
                                     "-o",
                                     pvs.string(),
                                     "--report",
                                     report.string(),
                                     "--threads",
                                     std::to_string(threads),
                                     "--quiet"};
    args.insert(args.end(), city.options.begin(), city.options.end());
    with_options(args, extra);
    std::vector<const char*> argp;
    for (const std::string& a : args) argp.push_back(a.c_str());
    const int rc = in_child([&] {
      if (!tool.empty()) {
        argp.push_back(nullptr);
        ::execv(tool.c_str(), const_cast<char* const*>(argp.data()));
        std::fprintf(stderr, "preprocess_benchmark: cannot run %s\n", tool.c_str());
        return 127;
      }
      preprocess::PreprocessRequest request;
      if (const auto stop = preprocess::parse_preprocess_command_line(static_cast<int>(argp.size()),
                                                                      argp.data(), request))
        return *stop;
      return preprocess::run_preprocess(request);
    });
    if (city.km2 > 0) fs::remove(city.input);
    if (rc != 0) {
      std::fprintf(stderr, "preprocess_benchmark: the bake of %s failed (exit %d)\n",
                   city.name.c_str(), rc);
      status = 1;
      continue;
    }
    std::ifstream in(report);
    const nlohmann::json r = nlohmann::json::parse(in);
    const auto& counts = r["counts"];
    const double cps = r["cells_per_second"].get<double>();
    const std::string change =
        pvs_change(pvs, compare.empty() ? fs::path{} : compare / (stem + ".pvs"));
    const double ms_per_cell = cps > 0 ? 1000.0 * threads / cps : 0.0;
    const double pvs_mean = counts["pvs_mean"].get<double>();
    char row[384];
    std::snprintf(row, sizeof row,
                  "| %s | %llu | %llu | %.1f | %.1f | %.1f | %.0f | %.1f | %.1f | %s |",
                  city.name.c_str(), counts["objects"].get<unsigned long long>(),
                  counts["cells"].get<unsigned long long>(), cps, ms_per_cell,
                  pvs_mean > 0 ? 1000.0 * ms_per_cell / pvs_mean : 0.0,
                  r["peak_memory_bytes"].get<double>() / (1024.0 * 1024.0), pvs_mean,
                  100.0 * counts["fraction_culled"].get<double>(), change.c_str());
    rows.push_back(row);
    std::fprintf(stderr, "%s\n", row);
    if (!save.empty())
      fs::copy_file(pvs, save / (stem + ".pvs"), fs::copy_options::overwrite_existing);
    fs::remove(pvs);
    fs::remove(report);
  }
  fs::remove_all(dir);
  std::printf("threads: %u%s%s%s%s\n", threads,
              tool.empty() ? "" : ", tool: ", tool.empty() ? "" : tool.c_str(),
              bake_options.empty() ? "" : ", bake options: ", bake_options.c_str());
  std::printf(
      "| city | objects | cells | cells/s | thread-ms/cell | thread-µs/PVS entry | peak MiB | mean "
      "PVS | culled %% | PVS vs before |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& row : rows) std::printf("%s\n", row.c_str());
  return status;
}
