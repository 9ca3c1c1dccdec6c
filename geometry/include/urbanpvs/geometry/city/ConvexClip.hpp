// SPDX-License-Identifier: GPL-3.0-or-later
// Clipping a convex polygon by a half-plane: one Sutherland–Hodgman step, for every stage that
// clips: the terrain's squares (TerrainOccluders), the ground under a cell (GroundHeight) and
// the occluder shadows (OccluderShadow). The caller says which side is kept and where an edge is
// cut, since those differ: a shadow's cut lies exactly on the clip box's side (its pixels must
// not move by a rounding), and a terrain piece carries its heights along the cut edge.
#pragma once

#include <cstddef>

namespace urbanpvs::geometry {

/// Appends to `out` the part of the convex polygon `in` where side(p) >= 0: the corners kept,
/// in order, and where an edge p -> q crosses the line, the point cut(p, q, side(p), side(q)).
/// A convex polygon gains at most one corner. `in` indexes like an array (size(), []); `out`
/// has push_back.
template <class Polygon, class Out, class Side, class Cut>
void clip_convex(const Polygon& in, Out& out, Side&& side, Cut&& cut) {
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = in[i];
    const auto& q = in[(i + 1) % n];
    const double sp = side(p), sq = side(q);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back(cut(p, q, sp, sq));
  }
}

}  // namespace urbanpvs::geometry
