// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/TerrainPyramid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "urbanpvs/geometry/occluders/TerrainOccluders.hpp"

namespace urbanpvs::preprocess {
namespace {

using geometry::Vec2;

constexpr std::int32_t kAbsent = -1;

}  // namespace

TerrainPyramid::TerrainPyramid(std::span<const geometry::Occluder> squares, double side)
    : side_(side) {
  if (squares.empty() || !(side > 0)) return;
  // The grid: squares of one side, placed from the least corner on.
  Vec2 origin{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (const geometry::Occluder& s : squares) {
    origin.x = std::min(origin.x, s.bounds.min.x);
    origin.y = std::min(origin.y, s.bounds.min.y);
  }
  auto index = [&](double v, double o) { return std::llround((v - o) / side); };
  long long columns = 0, rows = 0;
  for (const geometry::Occluder& s : squares) {
    columns = std::max(columns, index(s.bounds.min.x, origin.x) + 1);
    rows = std::max(rows, index(s.bounds.min.y, origin.y) + 1);
  }
  std::vector<std::int32_t> level(static_cast<std::size_t>(columns * rows), kAbsent);
  for (const geometry::Occluder& s : squares) {
    Node n;
    n.occluder = s;
    n.box.xy = s.bounds;
    n.box.zmin = -std::numeric_limits<double>::infinity();  // prisms stand on the ground
    n.box.zmax = s.top_high();
    const auto at = static_cast<std::size_t>(index(s.bounds.min.y, origin.y) * columns +
                                             index(s.bounds.min.x, origin.x));
    level[at] = static_cast<std::int32_t>(nodes_.size());
    nodes_.push_back(std::move(n));
  }
  std::vector<bool> has_parent(nodes_.size(), false);
  for (std::uint32_t l = 1; l <= kMaxLevel && columns > 1 && rows > 1; ++l) {
    const long long up_columns = (columns + 1) / 2, up_rows = (rows + 1) / 2;
    std::vector<std::int32_t> up(static_cast<std::size_t>(up_columns * up_rows), kAbsent);
    for (long long j = 0; j < up_rows; ++j)
      for (long long i = 0; i < up_columns; ++i) {
        std::int32_t child[4];
        bool complete = 2 * i + 1 < columns && 2 * j + 1 < rows;
        for (int k = 0; k < 4 && complete; ++k) {
          const long long ci = 2 * i + (k & 1), cj = 2 * j + (k >> 1);
          child[k] = level[static_cast<std::size_t>(cj * columns + ci)];
          complete = child[k] != kAbsent;
        }
        if (!complete) continue;
        Node n;
        n.level = l;
        geometry::Occluder& o = n.occluder;
        o.block = geometry::kTerrainBlock;
        // The children's mean gradient (any plane stays conservative once lowered below them).
        Vec2 slope{0, 0};
        n.box.zmin = -std::numeric_limits<double>::infinity();
        n.box.zmax = -std::numeric_limits<double>::infinity();
        for (const std::int32_t c : child) {
          const Node& cn = nodes_[static_cast<std::size_t>(c)];
          slope += 0.25 * cn.occluder.slope;
          o.bounds.extend(cn.occluder.bounds);
          n.box.zmax = std::max(n.box.zmax, cn.box.zmax);
        }
        o.slope = slope;
        o.origin = 0.5 * (o.bounds.min + o.bounds.max);
        o.shape.outer = o.bounds.corners();
        // Under every child's top at its corners, so under it over its whole square (both are
        // planes); rounding of the heights a few ulps: 0.1 µm lower.
        double least = std::numeric_limits<double>::infinity();
        for (const std::int32_t c : child) {
          const geometry::Occluder& co = nodes_[static_cast<std::size_t>(c)].occluder;
          for (const Vec2& p : co.bounds.corners())
            least = std::min(least, co.top_at(p) - (slope.x * (p.x - o.origin.x) +
                                                    slope.y * (p.y - o.origin.y)));
        }
        o.top_z = least - 1e-7;
        for (const std::int32_t c : child) {
          const Node& cn = nodes_[static_cast<std::size_t>(c)];
          for (const Vec2& p : cn.occluder.bounds.corners())
            n.drop = std::max(n.drop, cn.occluder.top_at(p) + cn.drop - o.top_at(p));
        }
        n.box.xy = o.bounds;
        for (int k = 0; k < 4; ++k) {
          n.child[k] = child[k];
          has_parent[static_cast<std::size_t>(child[k])] = true;
        }
        up[static_cast<std::size_t>(j * up_columns + i)] = static_cast<std::int32_t>(nodes_.size());
        nodes_.push_back(std::move(n));
        has_parent.push_back(false);
      }
    level = std::move(up);
    columns = up_columns;
    rows = up_rows;
  }
  for (std::uint32_t k = 0; k < nodes_.size(); ++k)
    if (!has_parent[k]) roots_.push_back(k);
}

}  // namespace urbanpvs::preprocess
