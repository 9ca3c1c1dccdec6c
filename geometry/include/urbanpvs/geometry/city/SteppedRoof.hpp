// SPDX-License-Identifier: GPL-3.0-or-later
// The occluder of a building part as a stepped height field under its own surfaces (thesis
// 7.3.2, 7.4): instead of one prism cut at the lowest point of the whole roof, one level per
// height at which the roof changes, each spanning only the ground where every surface above it
// is at least that high. The levels are nested prisms standing on the part's ground, so the
// block stage fuses and shrinks them level by level as before, and a level eroded by ε in 2D
// is the 2.5D erosion of the stepped field by the vertical cylinder of radius ε (thesis 7.4):
// for p in the eroded level at height h, every q within ε of p lies in the level, where the
// field is at least h.
#pragma once

#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// One surface of a part that may bound its solid from above (a roof, a terrace, a leaning
/// wall, a ceiling), seen in plan.
struct RoofFace {
  std::vector<Polygon> plan;  ///< its projection to the ground plane, valid polygons
  double low = 0;             ///< its lowest point [Units: m]
  double high = 0;            ///< its highest point [Units: m]
  /// A sloped face is planar within `deviation` at each vertex: z(p) = z0 + slope·(p − origin).
  /// A face that is not sloped counts as lying at `low` all over.
  bool sloped = false;
  Vec2 origin{0, 0};
  double z0 = 0;
  Vec2 slope{0, 0};
  double deviation = 0;  ///< [Units: m]
};

/// The face through these 3D rings (outer first, then holes) with its plan, as RoofFace wants
/// it; `plan` is the rings' projection, cleaned by the caller.
RoofFace roof_face(const std::vector<std::vector<Vec3>>& rings, std::vector<Polygon> plan);

/// The occluder prisms of a part standing at `ground_z` on `base` (its ground plan), under
/// `faces` (every surface of the part that may bound it from above; must not be empty).
///
/// The field is f(p) = the lowest of the faces above p, each counted at its lowest point or, if
/// sloped, at the highest level below it: so f never exceeds the first surface a vertical line
/// from the ground meets, whatever the faces' types or orientations say. Levels lie at every
/// face's lowest point and, on sloped faces, every `roof_step` above it (0: none between).
/// Points of `base` under no face get only the lowest level, as the whole part did before.
/// Levels closer than 5 cm merge into the lower one.
std::vector<OccluderPrism> stepped_occluders(const std::vector<Polygon>& base, double ground_z,
                                             const std::vector<RoofFace>& faces, double roof_step);

}  // namespace urbanpvs::geometry
