// SPDX-License-Identifier: GPL-3.0-or-later
// The occluders of a part's roof faces with their slopes kept (thesis 4.2.1, 7.3.2): under each
// face that rises above the part's flat occluder, the prism up to the face's own plane. A
// gabled roof then occludes up to near its ridge with the four walls of each face, where a
// stepped field (SteppedRoof.hpp) needs a level every few metres, each with all its walls.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/geometry/city/SteppedRoof.hpp"

namespace urbanpvs::geometry {

/// The prisms of a part standing at `ground_z` on `base` (its ground plan) under those of
/// `faces` (every surface of the part that may bound it from above) that reach more than
/// 10 cm above `above` (the top of the part's flat occluder).
///
/// A face's prism spans the ground under it and in `base`, less the plan of every other face
/// that may lie lower there (a ceiling under it, a dormer's roof that cuts into it), so a
/// vertical line from the ground meets this face first. Its top is the face's plane lowered by
/// the face's deviation from it and 1 mm (a flat face: its lowest point), so it lies nowhere
/// above the face, however a viewer triangulates the face.
std::vector<RoofPrism> roof_prisms(const std::vector<Polygon>& base, double ground_z,
                                   const std::vector<RoofFace>& faces, double above);

}  // namespace urbanpvs::geometry
