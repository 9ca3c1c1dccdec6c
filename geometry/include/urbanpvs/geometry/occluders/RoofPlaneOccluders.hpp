// SPDX-License-Identifier: GPL-3.0-or-later
// The roof prisms (RoofPrisms.hpp) of each block shrunk by ε in 2.5D (thesis 7.4: erosion of the
// height field by the vertical cylinder of radius ε), keeping their sloped tops, whose edges
// cast the shadows of sloped edges (thesis 4.2.1).
//
// Each face's plane L_i is lowered by ε times its steepest slope: L'_i(p) = L_i(p) − ε·|∇L_i|,
// the lowest L_i takes within ε of p. Face i's occluder spans the points p of
//   U ⊖ ε (the union U of the block's prisms, eroded by ε, so every point within ε of p lies
//   under some face) near face i, less every point p within ε of another face j (a mitred
//   offset of its ground, which holds that disk) where L'_i(p) > L'_j(p).
// So for every q within ε of p, under face j: roof(q) ≥ L_j(q) ≥ L'_j(p) ≥ L'_i(p), the
// occluder's top at p (j = i included). At a ridge the two faces' occluders meet on the line
// where their lowered planes cross, at the ridge's height less ε·slope: where eroding each face
// alone would lose a strip 2ε wide and as much again in height.
#pragma once

#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/geometry/occluders/Blocks.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"

namespace urbanpvs::geometry {

/// Occluder::block of a roof plane's occluder: it stands on the block's roofs, not in its levels.
inline constexpr std::uint32_t kRoofPlaneBlock = 0xFFFFFFFDu;

/// The occluders of the roof prisms of the occluding objects of each of `blocks`, shrunk by
/// `epsilon` (m, > 0). Slivers between faces narrower than options.gap_tolerance close, and
/// outlines are simplified within options.outline_tolerance, as for the blocks' levels; the
/// erosion grows by both. Blocks are shrunk on `threads` threads; the result is the same for
/// any number: blocks in order, faces in object order.
std::vector<Occluder> roof_plane_occluders(const std::vector<CityObject>& objects,
                                           const std::vector<Block>& blocks, double epsilon,
                                           const BlockOptions& options, unsigned threads = 1);

}  // namespace urbanpvs::geometry
