// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/CellOrder.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace urbanpvs::preprocess {
namespace {

constexpr int kOrder = 16;  // a 65,536² lattice over the cells' bounds: centimetres at 650 m

// The distance along the Hilbert curve of order kOrder of lattice point (x, y): the quadrant of
// each level in turn, the point rotated into the sub-curve's frame at each step.
std::uint64_t hilbert_distance(std::uint32_t x, std::uint32_t y) {
  std::uint64_t d = 0;
  for (std::uint32_t s = 1u << (kOrder - 1); s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0;
    const std::uint32_t ry = (y & s) ? 1 : 0;
    d += std::uint64_t{s} * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = s - 1 - (x & (s - 1));
        y = s - 1 - (y & (s - 1));
      }
      std::swap(x, y);
    }
    x &= s - 1;
    y &= s - 1;
  }
  return d;
}

}  // namespace

std::vector<std::uint32_t> along_hilbert_curve(const geometry::ViewCellMesh& mesh,
                                               std::span<const std::uint32_t> cells) {
  const geometry::Box2& b = mesh.bounds;
  const double side = std::max({b.max.x - b.min.x, b.max.y - b.min.y, 1e-9});
  const double scale = ((1u << kOrder) - 1) / side;
  auto lattice = [&](double v, double lo) {
    return static_cast<std::uint32_t>(std::clamp((v - lo) * scale, 0.0, (1u << kOrder) - 1.0));
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(cells.size());
  for (std::uint32_t c : cells) {
    const auto& corner = mesh.cells[c].corner;
    const geometry::Vec2 centroid = (corner[0] + corner[1] + corner[2]) / 3.0;
    keyed.emplace_back(hilbert_distance(lattice(centroid.x, b.min.x), lattice(centroid.y, b.min.y)),
                       c);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> out;
  out.reserve(keyed.size());
  for (const auto& k : keyed) out.push_back(k.second);
  return out;
}

}  // namespace urbanpvs::preprocess
