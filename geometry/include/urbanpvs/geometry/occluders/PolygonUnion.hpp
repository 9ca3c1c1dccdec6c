// SPDX-License-Identifier: GPL-3.0-or-later
// Exact union (and intersection, difference) of footprints (CGAL Boolean set operations with an
// exact kernel): buildings that share a wall become one polygon without a sliver between them
// (thesis 5.4: connected buildings occlude as one block).
#pragma once

#include <memory>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

/// The union of `polys` as disjoint, strictly simple polygons with holes (outer CCW, holes CW),
/// collinear vertices removed. Where the exact union only touches itself at a point, that point
/// is pulled 1 µm into the region, so the result is a subset of the exact union (never larger).
/// Input polygons must be valid (see polygon_defect).
std::vector<Polygon> union_polygons(const std::vector<Polygon>& polys);

/// The parts of `a` inside `b`, and of `a` outside `b`, exactly, with the results made as
/// union_polygons makes its own (a subset of the exact result). Either side may overlap itself.
/// A union that grows, kept exact between additions: a block's levels from the top down each
/// add their footprints to those above, and re-joining every footprint for every level cost
/// levels × footprints (minutes on a 3D BAG tile with stepped roofs).
class GrowingUnion {
 public:
  GrowingUnion();
  ~GrowingUnion();
  GrowingUnion(const GrowingUnion&) = delete;
  GrowingUnion& operator=(const GrowingUnion&) = delete;
  void add(const std::vector<Polygon>& polys);
  /// The union so far, as union_polygons gives it.
  std::vector<Polygon> polygons() const;

 private:
  struct Exact;
  std::unique_ptr<Exact> exact_;
};

std::vector<Polygon> intersect_polygons(const std::vector<Polygon>& a,
                                        const std::vector<Polygon>& b);
std::vector<Polygon> subtract_polygons(const std::vector<Polygon>& a,
                                       const std::vector<Polygon>& b);

}  // namespace urbanpvs::geometry
