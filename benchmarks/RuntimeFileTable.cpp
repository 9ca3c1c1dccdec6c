// SPDX-License-Identifier: MIT
// `runtime_benchmark --files A.pvs [B.pvs ...]`: what the runtime costs on real bakes. Each file
// is read back into a bake and re-encoded as format 1.0, 2.0 and 2.2 (so one run shows before and
// after on the same content); each encoding prints a table row: bytes per cell by section, the
// ratio of the whole file to plain 32-bit lists, the load time (full validation and checksums),
// and the latency of locate + iterating the PVS for one walking camera, for 200 walking agents
// queried round-robin (by a decoder that keeps one cell, and by one that keeps 256), the same walks
// located from each agent's last cell (locate_from), and for random points, p50 and p99, one
// query timed at a time.
#include "RuntimeFileTable.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "MemoryLatency.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::bench {
namespace {

namespace rt = urbanpvs::runtime;
using Clock = std::chrono::steady_clock;
using Point = std::array<double, 3>;

/// The file's content as a bake, through the public API only.
rt::PvsBake bake_of(const rt::PvsFile& file) {
  rt::PvsBake bake;
  const rt::FrameInfo frame = file.frame();
  bake.meta.frame.crs = std::string(frame.crs);
  bake.meta.frame.geographic = frame.geographic;
  bake.meta.frame.geodetic_origin = frame.geodetic_origin;
  bake.meta.frame.origin = frame.origin;
  bake.meta.settings = file.settings();
  for (std::size_t i = 0; i < file.property_count(); ++i) {
    std::string_view k, v;
    file.property(i, k, v);
    bake.meta.properties.emplace_back(std::string(k), std::string(v));
  }
  // Without the payloads (a 2.1 addition that 1.0 cannot hold): every row compares the same
  // cells and PVSs.
  for (std::uint32_t i = 0; i < file.object_count(); ++i) {
    rt::ObjectInfo o;
    file.object(i, o);
    bake.objects.push_back({std::string(o.source_id), o.bbox, {}});
  }
  rt::PvsDecoder decoder(file);
  for (std::uint32_t c = 0; c < file.cell_count(); ++c) {
    rt::CellGeometry g;
    file.cell(c, g);
    rt::CellRecord rec;
    rec.triangle = g.triangle;
    rec.z_min = g.z_min;
    rec.z_max = g.z_max;
    rec.neighbours = g.neighbours;
    decoder.decode(c);
    rec.pvs.assign(decoder.begin(), decoder.end());
    bake.cells.push_back(std::move(rec));
  }
  return bake;
}

Point inside(const rt::CellGeometry& g, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  double a = u(rng), b = u(rng);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  const auto& t = g.triangle;
  return {t[0].x + a * (t[1].x - t[0].x) + b * (t[2].x - t[0].x),
          t[0].y + a * (t[1].y - t[0].y) + b * (t[2].y - t[0].y), 0.5 * (g.z_min + g.z_max)};
}

/// Points inside random cells, at mid eye height: every query lands somewhere new.
std::vector<Point> random_points(const rt::PvsFile& file, std::size_t n) {
  std::mt19937_64 rng(42);
  std::vector<Point> out(n);
  rt::CellGeometry g;
  for (Point& p : out) {
    file.cell(static_cast<std::uint32_t>(rng() % file.cell_count()), g);
    p = inside(g, rng);
  }
  return out;
}

/// `count` agents walking 1.4 m per query through the free space, queried round-robin (one: a
/// walking camera; 200: a simulator's crowd in one frame loop). An agent that would leave the
/// cells turns instead.
std::vector<Point> walk_points(const rt::PvsFile& file, std::size_t n, std::size_t count) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> turn(-0.3, 0.3), angle(0, 6.2831853);
  struct Agent {
    Point p;
    double heading;
  };
  std::vector<Agent> agents(count);
  rt::CellGeometry g;
  for (Agent& a : agents) {
    file.cell(static_cast<std::uint32_t>(rng() % file.cell_count()), g);
    a = {inside(g, rng), angle(rng)};
  }
  std::vector<Point> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    Agent& a = agents[i % agents.size()];
    for (int attempt = 0; attempt < 8; ++attempt) {
      a.heading += attempt == 0 ? turn(rng) : angle(rng);
      const double x = a.p[0] + 1.4 * std::cos(a.heading), y = a.p[1] + 1.4 * std::sin(a.heading);
      const std::uint32_t c = file.locate_xy(x, y);
      if (c == rt::kNoCell) continue;
      file.cell(c, g);
      a.p = {x, y, 0.5 * (g.z_min + g.z_max)};
      break;
    }
    out[i] = a.p;
  }
  return out;
}

struct Latency {
  double p50 = 0, p99 = 0;
};

/// `agents` > 0: the points are those agents' steps in turn, and each is located from the cell
/// of its agent's last step (PvsFile::locate_from), as a camera or a simulator that keeps it.
Latency time_queries(const rt::PvsFile& file, const std::vector<Point>& points,
                     std::size_t cached_cells = 1, std::size_t agents = 0) {
  rt::PvsDecoder decoder(file, cached_cells);
  std::vector<std::uint32_t> last(std::max<std::size_t>(agents, 1), rt::kNoCell);
  std::vector<double> ns;
  ns.reserve(points.size());
  const double overhead = timer_overhead_ns();
  std::uint64_t sink = 0;
  for (int round = 0; round < 3; ++round) {  // the last round is kept: caches warm as in a game
    ns.clear();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Point& p = points[i];
      std::uint32_t& hint = last[agents > 0 ? i % agents : 0];
      const auto t0 = Clock::now();
      const std::uint32_t cell =
          agents > 0 ? file.locate_from(hint, p[0], p[1], p[2]) : file.locate(p[0], p[1], p[2]);
      hint = cell;
      if (cell != rt::kNoCell && decoder.decode(cell) == rt::Status::kOk) {
        for (std::uint32_t o : decoder) sink += o;
      }
      const auto t1 = Clock::now();
      ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() - overhead);
    }
  }
  if (sink == 42) std::puts("");  // keep the loop
  std::sort(ns.begin(), ns.end());
  return {ns[ns.size() / 2], ns[ns.size() * 99 / 100]};
}

std::uint64_t section_length(const rt::PvsFile& file, rt::format::SectionId id) {
  for (std::size_t i = 0; i < file.section_count(); ++i) {
    if (file.section(i).id == static_cast<std::uint32_t>(id)) return file.section(i).length;
  }
  return 0;
}

void print_row(const std::string& name, const char* encoding, const std::vector<std::byte>& bytes,
               bool expand) {
  rt::LoadOptions options;
  options.expand_pvs = expand;
  rt::PvsFile file;
  double best_load = 1e30;
  for (int i = 0; i < 5; ++i) {
    const auto t0 = Clock::now();
    if (rt::PvsFile::open(bytes.data(), bytes.size(), file, options) != rt::Status::kOk) {
      std::printf("| %s | %s | does not load |\n", name.c_str(), encoding);
      return;
    }
    best_load = std::min(best_load, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  using Id = rt::format::SectionId;
  const double cells = file.cell_count();
  const double plain = 4.0 * static_cast<double>(file.total_pvs_entries());
  const auto per_cell = [&](Id id) {
    return static_cast<double>(section_length(file, id)) / cells;
  };
  const std::vector<Point> camera_walk = walk_points(file, 20000, 1);
  const Latency camera = time_queries(file, camera_walk);
  const std::vector<Point> crowd = walk_points(file, 20000, 200);
  const Latency walk = time_queries(file, crowd);
  // An expanded file reads its lists in place: a cache changes nothing there.
  char cached[64] = "–";
  if (!expand) {
    const Latency c = time_queries(file, crowd, 256);
    std::snprintf(cached, sizeof cached, "%.0f / %.0f", c.p50, c.p99);
  }
  // The same walks located from each agent's last cell (crowds with the cache of 256 cells).
  const Latency camera_from = time_queries(file, camera_walk, 1, 1);
  const Latency crowd_from = time_queries(file, crowd, expand ? 1 : 256, 200);
  const Latency random = time_queries(file, random_points(file, 20000));
  std::printf(
      "| %s | %s%s | %u | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | **%.3f** | %.2f (%.2f GB/s) | "
      "%.0f / %.0f | %.0f / %.0f | %s | %.0f / %.0f | %.0f / %.0f | %.0f / %.0f |\n",
      name.c_str(), encoding, expand ? ", expanded" : "", file.cell_count(),
      static_cast<double>(file.total_pvs_entries()) / cells,
      static_cast<double>(bytes.size()) / cells, per_cell(Id::kCells), per_cell(Id::kGrid),
      per_cell(Id::kPvs), per_cell(Id::kObjects), static_cast<double>(bytes.size()) / plain,
      best_load * 1e3, static_cast<double>(bytes.size()) / best_load / 1e9, camera.p50, camera.p99,
      walk.p50, walk.p99, cached, camera_from.p50, camera_from.p99, crowd_from.p50, crowd_from.p99,
      random.p50, random.p99);
}

}  // namespace

int run_file_table(int argc, char** argv) {
  std::puts(
      "| file | format | cells | mean PVS | file B/cell | cells B/cell | grid B/cell | pvs B/cell "
      "| "
      "objects B/cell | file / plain lists | load ms | 1 camera p50 / p99 ns | 200 walkers p50 / "
      "p99 ns | 200 walkers, 256 cells cached, p50 / p99 ns | 1 camera, locate_from its last "
      "cell, p50 / p99 ns | 200 walkers, locate_from, 256 cells cached, p50 / p99 ns | random "
      "p50 / p99 ns |");
  std::puts("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
  for (int i = 0; i < argc; ++i) {
    rt::PvsFile file;
    rt::LoadError error;
    if (rt::PvsFile::open_file(argv[i], file, {}, &error) != rt::Status::kOk) {
      std::fprintf(stderr, "%s: %s\n", argv[i], error.detail);
      return 1;
    }
    std::string name = argv[i];
    name = name.substr(name.find_last_of('/') + 1);
    const rt::PvsBake bake = bake_of(file);
    rt::EncodeOptions v1;
    v1.format_major = 1;
    print_row(name, "1.0", rt::encode(bake, v1), false);
    rt::EncodeOptions varint;
    varint.pvs_coding = rt::PvsCoding::kVarint;
    const std::vector<std::byte> v20 = rt::encode(bake, varint);
    print_row(name, "2.0", v20, false);
    print_row(name, "2.0", v20, true);
    const std::vector<std::byte> v22 = rt::encode(bake);  // the default: coded PVS
    print_row(name, "2.2", v22, false);
    print_row(name, "2.2", v22, true);
  }
  // The floor under the random queries: each miss that waits for the one before costs this.
  std::printf(
      "\nMemory latency on this machine (dependent loads in random order, huge pages): %.0f ns "
      "per load over 64 MiB, %.0f ns over 8 MiB, %.0f ns over 1 MiB\n",
      memory_latency_ns(std::size_t{64} << 20), memory_latency_ns(std::size_t{8} << 20),
      memory_latency_ns(std::size_t{1} << 20));
  return 0;
}

}  // namespace urbanpvs::bench
