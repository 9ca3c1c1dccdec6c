// SPDX-License-Identifier: GPL-3.0-or-later
// Point location in the view cells for the preprocessor and tests: which cell holds a viewpoint
// (x, y). The runtime library has its own, over the cells stored in a PVS file.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "urbanpvs/geometry/cells/ViewCells.hpp"

namespace urbanpvs::geometry {

class CellLocator {
 public:
  /// Copies the cells' triangles, so the locator does not depend on the mesh's lifetime.
  explicit CellLocator(const ViewCellMesh& mesh);
  ~CellLocator();
  CellLocator(CellLocator&&) noexcept;
  CellLocator& operator=(CellLocator&&) noexcept;
  CellLocator(const CellLocator&) = delete;
  CellLocator& operator=(const CellLocator&) = delete;

  /// The index of the cell whose closed triangle contains p, decided with exact predicates; the
  /// smallest such index when p lies on an edge or vertex shared by several cells; -1 when p is
  /// in no cell (inside a building, outside the region, NaN).
  std::int32_t locate(Vec2 p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace urbanpvs::geometry
