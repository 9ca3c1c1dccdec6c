// SPDX-License-Identifier: GPL-3.0-or-later
// The roof that OpenStreetMap's roof:shape describes over a footprint, as planar 3D faces: what
// the GeoJSON and OSM readers give a pitched roof above its eaves instead of an empty space the
// roof may or may not fill. Its faces become the validator's blocking surfaces, and the prisms
// under them (RoofPrisms.hpp) occluders whose sloped edges cast shadows (thesis 4.2.1, 7.3.2).
//
// Thesis 7.1: an occluder must lie inside the building. Every model rises from the eaves E to
// the top T as z(p) = E + (T - E)·g(p) with g in [0, 1], and lies nowhere above any roof the
// tags allow:
//   gabled (and round, gambrel, whose profiles bulge above its straight slopes) with
//     roof:orientation given: the ridge along the longer sides (along) or across them;
//   gabled without roof:orientation, and hipped (half-hipped, mansard): the pyramid over the
//     rectangle. It is the lower envelope of the gables of both ridge directions, and of hipped
//     roofs of every ridge length (the tags give neither a hip's slope nor its ridge's length);
//   pyramidal (convex footprints), skillion (with roof:direction).
// Other shapes (dome, onion, cone, saltbox, ...) and footprints that do not suit the model get
// none: the reader then keeps the roof as a space it may fill, as before. The caller gives E
// and T only where the tags give them in metres (RoofShapes are not built on guessed storey
// heights: eaves above the real ones would lift the whole model above the roof).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

/// roof:orientation: the ridge along the longer sides or across them; Unknown when not tagged.
enum class RidgeOrientation { Unknown, Along, Across };

/// The tags that shape a roof.
struct RoofShapeTags {
  std::string shape;  ///< roof:shape, lower case
  /// roof:direction: the way the roof faces (downhill), degrees clockwise from north.
  std::optional<double> direction;
  RidgeOrientation ridge = RidgeOrientation::Unknown;
};

/// A modelled roof: open rings in the footprint's frame, heights absolute like its eaves and top.
struct ShapedRoof {
  std::vector<std::vector<Vec3>> faces;  ///< planar faces from the eaves up: triangles, quads
  std::vector<std::vector<Vec3>> walls;  ///< vertical walls above the eaves (gables, high sides)
};

/// The roof over `footprint` (a cleaned polygon: counter-clockwise outer ring) with walls up to
/// `eaves` and its top at `top`, or nothing when the shape is none of those modelled or the
/// footprint does not suit it: gabled and hipped roofs need a rectangle (corners square within
/// 10°, once vertices less than 10 cm outside its sides or 2 cm inside them are dropped, and no
/// vertex more than 2 cm inside it, so that it lies within the footprint up to the rounding of
/// OSM's coordinates), pyramidal roofs a convex footprint, skillions a roof:direction; none
/// has holes.
std::optional<ShapedRoof> shaped_roof(const Polygon& footprint, const RoofShapeTags& tags,
                                      double eaves, double top);

/// roof:direction as degrees clockwise from north: a number, or a compass point (N, NNE, ... NNW,
/// any case). Nothing when it is neither.
std::optional<double> roof_direction(std::string_view text);

}  // namespace urbanpvs::geometry
