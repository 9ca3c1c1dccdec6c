// SPDX-License-Identifier: GPL-3.0-or-later
// A uniform grid of buckets, each listing the cells whose bounding box overlaps it, in ascending
// order: the first containing cell found is the smallest index containing p, which makes the
// answer on shared edges deterministic. CGAL's filtered predicates make the test exact at the
// cost of a few nanoseconds.
#include "urbanpvs/geometry/cells/CellLocator.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "BoxGrid.hpp"

namespace urbanpvs::geometry {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

bool contains(const std::array<K::Point_2, 3>& t, const K::Point_2& p) {
  return CGAL::orientation(t[0], t[1], p) != CGAL::RIGHT_TURN &&
         CGAL::orientation(t[1], t[2], p) != CGAL::RIGHT_TURN &&
         CGAL::orientation(t[2], t[0], p) != CGAL::RIGHT_TURN;
}

}  // namespace

struct CellLocator::Impl {
  std::vector<std::array<K::Point_2, 3>> triangles;
  detail::BoxGrid grid;
};

CellLocator::CellLocator(const ViewCellMesh& mesh) : impl_(std::make_unique<Impl>()) {
  std::vector<Box2> boxes;
  boxes.reserve(mesh.cells.size());
  impl_->triangles.reserve(mesh.cells.size());
  for (const ViewCell& c : mesh.cells) {
    Box2 b;
    std::array<K::Point_2, 3> t;
    for (std::size_t k = 0; k < 3; ++k) {
      b.extend(c.corner[k]);
      t[k] = {c.corner[k].x, c.corner[k].y};
    }
    boxes.push_back(b);
    impl_->triangles.push_back(t);
  }
  impl_->grid = detail::BoxGrid(boxes, 1.0);
}

CellLocator::~CellLocator() = default;
CellLocator::CellLocator(CellLocator&&) noexcept = default;
CellLocator& CellLocator::operator=(CellLocator&&) noexcept = default;

std::int32_t CellLocator::locate(Vec2 p) const {
  const K::Point_2 q(p.x, p.y);
  for (std::uint32_t i : impl_->grid.at(p))
    if (contains(impl_->triangles[i], q)) return std::int32_t(i);
  return -1;
}

}  // namespace urbanpvs::geometry
