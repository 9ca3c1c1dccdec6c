// SPDX-License-Identifier: GPL-3.0-or-later
// The terrain's sloped squares (--terrain-planes) merged two by two, level after level, into
// coarser squares, for the far field's horizons: far from a sample, a horizon takes one coarse
// square instead of the many it covers. A coarse square's top is a plane that lies under each
// of its children's tops (checked at their corners: both are planes), over the children's
// ground, so its prism lies within theirs: it hides no more than they do, and what they are
// conservative for (thesis 7.4, the 2.5D erosion), it is too. The sight lines keep every
// square, and a pixel centre a horizon leaves open is traced exactly past them, so the PVS does
// not depend on which squares the horizons took: only the walls a sweep adds and the sight lines
// it traces do (README, "Terrain as an occluder").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "urbanpvs/geometry/occluders/Occluder.hpp"

namespace urbanpvs::preprocess {

class TerrainPyramid {
 public:
  struct Node {
    geometry::Occluder occluder;  ///< the square: a grid square, or one merged from 2 x 2
    geometry::Box3 box;           ///< its ground, up to the highest top in its subtree
    std::uint32_t level = 0;      ///< 0: a square of the grid; l: 2^l x 2^l of them
    double drop = 0;  ///< how far its top lies under the grid squares below it, at most (m)
    std::int32_t child[4] = {-1, -1, -1, -1};
  };

  /// A horizon takes a node's children instead of it while its distance from the sample is
  /// less than this many times the node's side: with 4, a square spans at most about 14° seen
  /// from the sample, and a sweep takes some hundreds of squares per level however large the
  /// terrain.
  static constexpr double kSplitRatio = 4;
  /// ... and while its top lies more than this share of the distance under the squares it
  /// covers (Node::drop): a crest keeps its detail, a plain or an even slope loses nothing by
  /// merging. On Andorra la Vella 5 % took the least time; 0.5 % and 2 % added walls, 10 % sight
  /// lines (README, "Terrain as an occluder"). The PVS is the same for any value.
  static constexpr double kDropPerDistance = 0.05;
  /// Levels above the grid's: 2^6 = 64 squares a side at the top (4 km of 64 m squares).
  static constexpr std::uint32_t kMaxLevel = 6;

  TerrainPyramid() = default;
  /// `squares`: the sloped squares of one grid of side `side` (terrain_plane_occluders), in any
  /// order. Four squares that make a square of the next level merge when all four are there.
  TerrainPyramid(std::span<const geometry::Occluder> squares, double side);

  bool empty() const { return nodes_.empty(); }
  const std::vector<Node>& nodes() const { return nodes_; }
  /// The nodes without a parent: the top level's, and those whose block of four is incomplete.
  const std::vector<std::uint32_t>& roots() const { return roots_; }
  /// Whether a horizon at ground distance `distance` from `n` takes its children instead.
  bool split(const Node& n, double distance) const {
    return n.level > 0 && (distance < kSplitRatio * side_ * static_cast<double>(1u << n.level) ||
                           n.drop > kDropPerDistance * distance);
  }

 private:
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> roots_;
  double side_ = 0;
};

}  // namespace urbanpvs::preprocess
