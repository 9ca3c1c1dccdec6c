// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/RoofPrisms.hpp"

#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

// A face must lift the occluder by more than this (m) to be worth its walls in every map.
constexpr double kMinGain = 0.1;
// Kept between the prism's top and the face's plane (m): rounding of the plane's fit, far
// below the occluder shrinking that follows.
constexpr double kPlaneMargin = 0.001;

Box2 plan_bounds(const RoofFace& f) {
  Box2 b;
  for (const Polygon& p : f.plan) b.extend(bounds(p));
  return b;
}

}  // namespace

std::vector<RoofPrism> roof_prisms(const std::vector<Polygon>& base, double ground_z,
                                   const std::vector<RoofFace>& faces, double above) {
  std::vector<RoofPrism> out;
  std::vector<Box2> boxes;
  boxes.reserve(faces.size());
  for (const RoofFace& f : faces) boxes.push_back(plan_bounds(f));
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const RoofFace& f = faces[i];
    RoofPrism prism;
    prism.ground_z = ground_z;
    if (f.sloped) {
      prism.origin = f.origin;
      prism.z0 = f.z0 - f.deviation - kPlaneMargin;
      prism.slope = f.slope;
    } else {
      prism.z0 = f.low;  // a face that is not sloped counts as lying at its lowest point
    }
    const double top = f.sloped ? f.high - f.deviation - kPlaneMargin : f.low;
    if (!(top > above + kMinGain)) continue;
    // Faces that may lie below this one where their plans overlap it: anything lower than its
    // top somewhere. Neighbours that only share an edge with it take nothing away.
    std::vector<Polygon> lower;
    for (std::size_t j = 0; j < faces.size(); ++j)
      if (j != i && faces[j].low < top && boxes[i].overlaps(boxes[j]))
        lower.insert(lower.end(), faces[j].plan.begin(), faces[j].plan.end());
    std::vector<Polygon> region = intersect_polygons(f.plan, base);
    if (!lower.empty() && !region.empty()) region = subtract_polygons(region, lower);
    for (Polygon& p : region) {
      // As in stepped_occluders: a piece that touches itself would crash the shrinking.
      if (!polygon_defect(p).empty()) continue;
      prism.footprint = std::move(p);
      out.push_back(prism);
    }
  }
  return out;
}

}  // namespace urbanpvs::geometry
