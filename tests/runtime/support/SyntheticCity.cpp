// SPDX-License-Identifier: MIT
#include "SyntheticCity.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace urbanpvs::test {
namespace {

using runtime::CellRecord;
using runtime::kNoCell;
using runtime::Point2;
using runtime::PvsBake;

struct Building {
  double x, y;   // centre
  double reach;  // near-field radius factor (taller buildings are seen farther)
  bool landmark;
};

/// Buckets of building indices on a coarse grid, to find the buildings near a point.
class BucketGrid {
 public:
  BucketGrid(const std::vector<Building>& b, double extent, double bucket)
      : bucket_(bucket), n_(static_cast<int>(std::ceil(extent / bucket))), cells_(n_ * n_) {
    for (std::uint32_t i = 0; i < b.size(); ++i) cells_[index(b[i].x, b[i].y)].push_back(i);
  }
  template <class F>
  void for_each_near(double x, double y, double radius, F f) const {
    const int x0 = clamp(static_cast<int>((x - radius) / bucket_));
    const int x1 = clamp(static_cast<int>((x + radius) / bucket_));
    const int y0 = clamp(static_cast<int>((y - radius) / bucket_));
    const int y1 = clamp(static_cast<int>((y + radius) / bucket_));
    for (int j = y0; j <= y1; ++j) {
      for (int i = x0; i <= x1; ++i) {
        for (std::uint32_t b : cells_[j * n_ + i]) f(b);
      }
    }
  }

 private:
  int clamp(int v) const { return std::clamp(v, 0, n_ - 1); }
  std::size_t index(double x, double y) const {
    return static_cast<std::size_t>(clamp(static_cast<int>(y / bucket_)) * n_ +
                                    clamp(static_cast<int>(x / bucket_)));
  }
  double bucket_;
  int n_;
  std::vector<std::vector<std::uint32_t>> cells_;
};

/// Near-field radius at a point: varies smoothly between ~0.55 and ~1.45 times the mean.
double near_radius(const SyntheticCityOptions& o, double x, double y) {
  return o.near_radius_m * (1 + 0.45 * std::sin(x / 410.0 + 0.3) * std::cos(y / 530.0 - 1.1));
}

void add_buildings(PvsBake& bake, std::vector<Building>& buildings, const SyntheticCityOptions& o,
                   std::mt19937_64& rng) {
  std::uniform_real_distribution<double> pos(0, o.extent_m), size(8, 30), u(0, 1);
  for (std::uint32_t i = 0; i < o.objects; ++i) {
    const double x = pos(rng), y = pos(rng), w = size(rng), d = size(rng);
    const bool landmark = u(rng) < o.landmark_fraction;
    const double height = landmark ? 60 + 90 * u(rng) : 6 + 30 * u(rng) * u(rng);
    bake.objects.push_back(
        {"bldg." + std::to_string(i), {x - w / 2, y - d / 2, 0, x + w / 2, y + d / 2, height}, {}});
    buildings.push_back({x, y, 0.7 + height / 60.0, landmark});
  }
}

void add_cells(PvsBake& bake, const SyntheticCityOptions& o) {
  const std::uint32_t n = o.squares;
  const double s = o.extent_m / n;
  auto tri = [&](std::uint32_t i, std::uint32_t j, int half) { return 2 * (j * n + i) + half; };
  bake.cells.resize(std::size_t{2} * n * n);
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const Point2 a{i * s, j * s}, b{(i + 1) * s, j * s}, c{(i + 1) * s, (j + 1) * s},
          d{i * s, (j + 1) * s};
      // Lower-right triangle a b c: edges ab (square below), bc (square right), ca (diagonal).
      CellRecord& lower = bake.cells[tri(i, j, 0)];
      lower.triangle = {a, b, c};
      lower.neighbours = {j > 0 ? tri(i, j - 1, 1) : kNoCell,
                          i + 1 < n ? tri(i + 1, j, 1) : kNoCell, tri(i, j, 1)};
      // Upper-left triangle a c d: edges ac (diagonal), cd (square above), da (square left).
      CellRecord& upper = bake.cells[tri(i, j, 1)];
      upper.triangle = {a, c, d};
      upper.neighbours = {tri(i, j, 0), j + 1 < n ? tri(i, j + 1, 0) : kNoCell,
                          i > 0 ? tri(i - 1, j, 0) : kNoCell};
      for (CellRecord* cell : {&lower, &upper}) {
        cell->z_min = 1.5;
        cell->z_max = 2.0;
      }
    }
  }
}

}  // namespace

PvsBake synthetic_city(const SyntheticCityOptions& o) {
  std::mt19937_64 rng(o.seed);
  PvsBake bake;
  bake.meta.frame.crs = "EPSG:7415";
  bake.meta.frame.origin = {84000, 444000, 0};
  bake.meta.settings = {0.1, 0.25, o.extent_m / o.squares, 1.5, 2.0, 0x5eedc17e5eedc17eULL};
  bake.meta.properties = {{"generator", "synthetic_city"}};
  std::vector<Building> buildings;
  add_buildings(bake, buildings, o, rng);
  add_cells(bake, o);
  const BucketGrid grid(buildings, o.extent_m, 100);
  const double max_reach = 0.7 + 150 / 60.0;
  std::vector<char> seen(buildings.size(), 0);
  for (CellRecord& cell : bake.cells) {
    const double cx = (cell.triangle[0].x + cell.triangle[1].x + cell.triangle[2].x) / 3;
    const double cy = (cell.triangle[0].y + cell.triangle[1].y + cell.triangle[2].y) / 3;
    const double r = near_radius(o, cx, cy);
    auto visit = [&](std::uint32_t b, double radius) {
      const double dx = buildings[b].x - cx, dy = buildings[b].y - cy;
      if (!seen[b] && dx * dx + dy * dy < radius * radius) {
        seen[b] = 1;
        cell.pvs.push_back(b);
      }
    };
    grid.for_each_near(cx, cy, r * max_reach,
                       [&](std::uint32_t b) { visit(b, r * buildings[b].reach); });
    grid.for_each_near(cx, cy, o.landmark_radius_m, [&](std::uint32_t b) {
      if (buildings[b].landmark) visit(b, o.landmark_radius_m);
    });
    std::sort(cell.pvs.begin(), cell.pvs.end());
    for (std::uint32_t b : cell.pvs) seen[b] = 0;
  }
  return bake;
}

}  // namespace urbanpvs::test
