// SPDX-License-Identifier: GPL-3.0-or-later
// A set of cells of a rectilinear lattice (columns between xs, rows between ys) traced into
// polygons: the shapes of the stepped occluders cut from rasters (the terrain's levels, the
// columns of shrunk solids). Both only ever need a subset of what they mark, so every step
// that could make a ring touch itself drops cells instead.
#pragma once

#include <cstddef>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

class LatticeMask {
 public:
  /// Lines xs (columns + 1 of them, increasing) and ys (rows + 1); no cell set.
  LatticeMask(std::vector<double> xs, std::vector<double> ys);

  int columns() const { return nu_; }
  int rows() const { return nv_; }
  bool get(int u, int v) const { return in_[index(u, v)] != 0; }
  void set(int u, int v, bool value) { in_[index(u, v)] = value ? 1 : 0; }
  bool full() const;
  const std::vector<unsigned char>& cells() const { return in_; }

  /// Where two cells meet only at a corner, one is cleared: the rings traced by polygons()
  /// then never touch themselves or each other (an occluder may always be smaller).
  void separate_diagonals();

  /// The set cells as polygons (outer rings counter-clockwise, holes clockwise), the lattice's
  /// border taken as their outside; false if the rings could not be assembled. Call
  /// separate_diagonals() first.
  bool polygons(std::vector<Polygon>& out) const;

 private:
  std::size_t index(int u, int v) const {
    return static_cast<std::size_t>(v) * static_cast<std::size_t>(nu_) +
           static_cast<std::size_t>(u);
  }
  Vec2 point(int u, int v) const {
    return {xs_[static_cast<std::size_t>(u)], ys_[static_cast<std::size_t>(v)]};
  }

  std::vector<double> xs_, ys_;
  int nu_, nv_;
  std::vector<unsigned char> in_;
};

}  // namespace urbanpvs::geometry
