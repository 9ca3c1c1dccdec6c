// SPDX-License-Identifier: MIT
#include "RandomBake.hpp"

#include <algorithm>
#include <deque>
#include <map>
#include <random>
#include <set>
#include <string>

namespace urbanpvs::test {
namespace {

using runtime::CellRecord;
using runtime::kNoCell;
using runtime::ObjectRecord;
using runtime::Point2;
using runtime::PvsBake;

void fill_metadata(PvsBake& bake, std::mt19937_64& rng, bool properties) {
  bake.meta.frame.crs = "EPSG:7415";
  bake.meta.frame.origin = {85000.0 + static_cast<double>(rng() % 1000), 446000.0, -2.5};
  bake.meta.settings = {0.25, 0.5, 12, 1.5, 2.0, rng()};
  if (properties) {
    bake.meta.properties = {{"generator", "random_bake"},
                            {"seed", std::to_string(rng() % 1000)},
                            {"unicode", "Zürich \xE2\x80\x94 caf\xC3\xA9"}};
  }
}

void fill_objects(PvsBake& bake, std::mt19937_64& rng, std::uint32_t count, double extent) {
  std::uniform_real_distribution<double> pos(-10, extent + 10), size(0.5, 20), height(3, 60);
  bake.objects.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const double x = pos(rng), y = pos(rng);
    bake.objects[i] = {
        "obj." + std::to_string(i), {x, y, 0, x + size(rng), y + size(rng), height(rng)}, {}};
  }
}

/// Random subset of [lo, hi) with the given density.
std::vector<std::uint32_t> random_set(std::mt19937_64& rng, std::uint32_t lo, std::uint32_t hi,
                                      double density) {
  std::vector<std::uint32_t> out;
  if (density >= 1) {
    for (std::uint32_t i = lo; i < hi; ++i) out.push_back(i);
    return out;
  }
  std::bernoulli_distribution in(density);
  for (std::uint32_t i = lo; i < hi; ++i) {
    if (in(rng)) out.push_back(i);
  }
  return out;
}

/// A parent's set with about (1 - coherence) of it replaced by other random ids.
std::vector<std::uint32_t> perturb(std::mt19937_64& rng, const std::vector<std::uint32_t>& parent,
                                   std::uint32_t lo, std::uint32_t hi, double coherence) {
  std::set<std::uint32_t> s(parent.begin(), parent.end());
  const std::size_t changes = static_cast<std::size_t>((1 - coherence) * parent.size() + 0.5);
  std::uniform_int_distribution<std::uint32_t> any(lo, hi > lo ? hi - 1 : lo);
  for (std::size_t k = 0; k < changes && !s.empty(); ++k) {
    s.erase(std::next(s.begin(), static_cast<long>(rng() % s.size())));
    if (hi > lo) s.insert(any(rng));
  }
  return {s.begin(), s.end()};
}

/// PVSs in breadth-first order, each derived from an already filled neighbour.
void fill_pvs(PvsBake& bake, std::mt19937_64& rng, const RandomBakeOptions& o) {
  const std::size_t n = bake.cells.size();
  std::vector<char> done(n, 0);
  for (std::size_t start = 0; start < n; ++start) {
    if (done[start]) continue;
    bake.cells[start].pvs = random_set(rng, o.min_object, o.objects, o.density);
    done[start] = 1;
    std::deque<std::size_t> queue{start};
    while (!queue.empty()) {
      const std::size_t c = queue.front();
      queue.pop_front();
      for (std::uint32_t nb : bake.cells[c].neighbours) {
        if (nb == kNoCell || done[nb]) continue;
        bake.cells[nb].pvs = perturb(rng, bake.cells[c].pvs, o.min_object, o.objects, o.coherence);
        done[nb] = 1;
        queue.push_back(nb);
      }
    }
  }
}

}  // namespace

PvsBake random_mesh_bake(std::uint64_t seed, const RandomBakeOptions& o) {
  std::mt19937_64 rng(seed);
  PvsBake bake;
  fill_metadata(bake, rng, o.properties);
  fill_objects(bake, rng, o.objects, o.square * std::max(o.nx, o.ny));
  // Jittered vertex grid; boundary vertices stay on the boundary.
  std::uniform_real_distribution<double> jitter(-o.jitter * o.square, o.jitter * o.square);
  std::vector<Point2> vertices;
  for (std::uint32_t j = 0; j <= o.ny; ++j) {
    for (std::uint32_t i = 0; i <= o.nx; ++i) {
      const double jx = (i == 0 || i == o.nx) ? 0 : jitter(rng);
      const double jy = (j == 0 || j == o.ny) ? 0 : jitter(rng);
      vertices.push_back({i * o.square + jx, j * o.square + jy});
    }
  }
  auto vid = [&](std::uint32_t i, std::uint32_t j) { return j * (o.nx + 1) + i; };
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (std::uint32_t j = 0; j < o.ny; ++j) {
    for (std::uint32_t i = 0; i < o.nx; ++i) {
      const std::uint32_t a = vid(i, j), b = vid(i + 1, j), c = vid(i + 1, j + 1),
                          d = vid(i, j + 1);
      if (rng() % 2) {  // counter-clockwise, random diagonal
        tris.push_back({a, b, c});
        tris.push_back({a, c, d});
      } else {
        tris.push_back({a, b, d});
        tris.push_back({b, c, d});
      }
    }
  }
  // Neighbours through shared edges.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<std::uint32_t, int>> edges;
  bake.cells.resize(tris.size());
  std::uniform_real_distribution<double> ground(-1, 3);
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    CellRecord& cell = bake.cells[t];
    for (int k = 0; k < 3; ++k) cell.triangle[k] = vertices[tris[t][k]];
    const double g = ground(rng);
    cell.z_min = g + 1.5;
    cell.z_max = g + 2.0;
    if (!o.neighbours) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = tris[t][k], v = tris[t][(k + 1) % 3];
      const auto key = std::minmax(u, v);
      auto it = edges.find(key);
      if (it == edges.end()) {
        edges[key] = {t, k};
      } else {
        cell.neighbours[k] = it->second.first;
        bake.cells[it->second.first].neighbours[it->second.second] = t;
      }
    }
  }
  fill_pvs(bake, rng, o);
  if (o.payloads) {  // drawn last, so the rest of the bake does not depend on it
    bake.payload_key = "mesh";
    for (std::uint32_t i = 0; i < bake.objects.size(); ++i) {
      if (rng() % 4 == 0) continue;
      bake.objects[i].payload = "m/" + std::to_string(rng() % 100000) + (i % 7 ? "" : "\xC3\xA9");
    }
  }
  return bake;
}

PvsBake random_soup_bake(std::uint64_t seed, std::uint32_t cells, double extent) {
  std::mt19937_64 rng(seed);
  PvsBake bake;
  fill_metadata(bake, rng, false);
  fill_objects(bake, rng, 20, extent);
  std::uniform_real_distribution<double> pos(0, extent), size(-extent / 8, extent / 8), z(-5, 5);
  bake.cells.resize(cells);
  for (CellRecord& c : bake.cells) {
    const Point2 a{pos(rng), pos(rng)};
    c.triangle = {a, Point2{a.x + size(rng), a.y + size(rng)},
                  Point2{a.x + size(rng), a.y + size(rng)}};
    c.z_min = z(rng);
    c.z_max = c.z_min + 4;
    c.pvs = random_set(rng, 0, 20, 0.3);
  }
  return bake;
}

}  // namespace urbanpvs::test
