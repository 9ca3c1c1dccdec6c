// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: exact point-in-ring tests for rings of any size. CGAL::bounded_side_2 walks every
// edge of the ring on each query; a street region is one ring of tens of thousands of vertices
// around a country's streets, asked about every vertex of its triangulation (the view cells'
// Nudger): 55 % of Liechtenstein's bake went there. Here the edges are filed in horizontal
// strips, and a query reads only the strip of its point.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::detail {

class RingLocator {
 public:
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;

  explicit RingLocator(const Ring& ring);

  /// Where p lies against the ring, exactly as CGAL::bounded_side_2 answers for the ring's
  /// points (the crossing rule with exact orientation predicates; a point on an edge or a vertex
  /// is ON_BOUNDARY). A ring of fewer than three points bounds nothing.
  CGAL::Bounded_side side(const K::Point_2& p) const;

 private:
  /// The strip of height y, clamped to the ring's (monotone in y).
  std::size_t strip_of(double y) const;

  std::vector<K::Point_2> points_;
  double xmin_ = 0, xmax_ = 0, ymin_ = 0, ymax_ = 0;
  double strip_ = 1;  ///< strip height
  std::size_t strips_ = 0;
  std::vector<std::uint32_t> start_;  ///< strips_ + 1 offsets into edges_
  std::vector<std::uint32_t> edges_;  ///< edge i runs from points_[i] to points_[i + 1 mod n]
};

/// A polygon's outer ring and holes, each located as above.
class PolygonLocator {
 public:
  explicit PolygonLocator(const Polygon& polygon);

  /// Strictly inside the outer ring and strictly outside every hole.
  bool strictly_inside(const RingLocator::K::Point_2& p) const;
  /// In the closed polygon: not outside the outer ring, not strictly inside a hole.
  bool inside_or_on(const RingLocator::K::Point_2& p) const;

 private:
  RingLocator outer_;
  std::vector<RingLocator> holes_;
};

}  // namespace urbanpvs::geometry::detail
