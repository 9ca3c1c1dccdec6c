// SPDX-License-Identifier: GPL-3.0-or-later
// Occluder shrinking in 3D (thesis 7.3.1) for buildings that are not height fields: overhangs,
// arcades, passages, bridges, parts stacked on other parts. The exterior of the building's
// closed surfaces is cut into tetrahedra (TetGen), each is enlarged by ε, and what of the
// building they leave is the shrunk solid. The visibility stages take ground-standing
// occluders only (thesis 4.2.1: an occluder shadow is cast by a prism that stands on the
// ground), so what is kept of the shrunk solid is its largest ground-standing part, as
// stepped levels like a block's.
//
// TetGen is AGPL-3.0-or-later: this route exists only in a build configured with
// URBANPVS_TETGEN=ON, which makes the preprocessor's binaries AGPL (README, "Licences").
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"

namespace urbanpvs::geometry {

/// Occluder::block of an occluder shrunk from a solid: it comes from no block.
inline constexpr std::uint32_t kSolidBlock = 0xFFFFFFFEu;

/// What shrinking one building's solid gave.
struct ShrunkSolid {
  /// Nested levels: for each top h, the squares whose whole column from the ground up to h
  /// lies in the solid at least ε (horizontally) from its outside.
  std::vector<Occluder> occluders;
  std::size_t exterior_tetrahedra = 0;
  /// Why the solid gave no occluders, e.g. TetGen refused its surfaces, or they do not close
  /// (the outside then reaches in everywhere); empty when it was shrunk.
  std::string declined;
};

/// Whether the building is not a height field over its footprint: a face of it looks down
/// from above the ground (the ceiling of an arcade, the underside of an overhang or a bridge).
/// Faces are taken as wound counter-clockwise seen from outside, as CityJSON and CityGML
/// require; a face wound the other way only decides whether the 3D route runs.
bool overhangs(const std::vector<Surface3>& surfaces, double ground_z);

/// Whether this build has the 3D route (URBANPVS_TETGEN=ON).
bool solid_shrinking_available();

/// Shrinks the solid bounded by the blocking `surfaces` (one building, all its parts: faces
/// shared by two parts are kept once; where the parts do not close as one solid, each part
/// (Surface3::part) is shrunk alone and their occluders are joined) by `epsilon` (m, > 0) in
/// the horizontal directions
/// (thesis 7.4: samples lie on the top face of a cell, so the cylinder of radius ε suffices)
/// and keeps its ground-standing part above `ground_z` as levels `step` (m, > 0) apart from
/// ground_z up. Every point p of an occluder of top h has, within ε of p horizontally, only
/// points inside the solid: each column is tested with a square of half-side ε plus half a
/// raster square around its centre, which holds the disk of radius ε around any point of it.
/// Conservative for every input: surfaces that leave a gap let the outside in and give
/// nothing; surfaces TetGen cannot mesh give nothing. Within these tolerances: vertices closer
/// than 0.1 mm are one (so a slit narrower than that is closed); a column may come within
/// 1e-7 m of the outside, and a level stand 1e-7 m above the solid; outside space lying wholly
/// within 1 cm above ground_z holds no column down; an open loop of edges within 25 cm above
/// ground_z is closed as the solid's bottom; where the faces close no volume as given (a roof
/// that overhangs its walls), a face is cut along other faces' edges whose ends lie within 5 mm
/// of its plane, and a vertex within 5 mm of an edge splits it, so a face may bend by 5 mm.
ShrunkSolid shrink_solid(const std::vector<Surface3>& surfaces, double ground_z, double epsilon,
                         double step);

}  // namespace urbanpvs::geometry

namespace urbanpvs::geometry {

/// One building for shrink_solids.
struct SolidInput {
  const std::vector<Surface3>* surfaces = nullptr;
  double ground_z = 0;
};

/// shrink_solid for every input, run in a child process (POSIX fork): TetGen 1.5 crashes on
/// some faces of real data and loops forever on others, and a bake must survive both. A
/// building whose child crashes, or takes longer than `seconds`, gives no occluders (declined
/// says which); a fresh child goes on with the next one. Results are in input order.
std::vector<ShrunkSolid> shrink_solids(const std::vector<SolidInput>& inputs, double epsilon,
                                       double step, double seconds);

/// As above, with `shrink` in place of shrink_solid (the tests' crashes and endless loops).
std::vector<ShrunkSolid> shrink_solids(const std::vector<SolidInput>& inputs, double seconds,
                                       const std::function<ShrunkSolid(const SolidInput&)>& shrink);

}  // namespace urbanpvs::geometry
