// Building solids: flat prisms (LoD1) and the three pitched roof constructions of LoD2.
//
// Each construction builds its faces from shared, snapped points and checks that the result is
// closed; a construction that cannot produce a clean solid for a shape returns nothing and the
// caller falls back to a simpler roof. No general straight skeleton is needed because the layout
// only produces three kinds of shapes: strips along a block's edge (perimeter blocks), convex
// slices (solid blocks, possibly with one convex light well) and rectangles (towers).
#pragma once

#include <optional>
#include <vector>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities::detail {

/// A building of a perimeter block: a strip between the block's street line and its courtyard
/// line. Station k joins outer[k] (street side) to inner[k] (courtyard side) by a cut wall or a
/// corner diagonal; consecutive stations lie on the same block side. A closed strip is the whole
/// ring around the courtyard (a building with a hole).
struct Strip {
  std::vector<Vec2> outer;
  std::vector<Vec2> inner;
  bool closed = false;
};

/// Footprint of a strip: open strips are outer then inner reversed; closed ones have the
/// courtyard as a hole.
Polygon stripFootprint(const Strip& strip);

/// The LoD1 prism: footprint extruded from z0 to z0 + height.
Solid flatSolid(const Polygon& footprint, double z0, double height);

struct RoofedSolid {
  Solid solid;
  RoofKind roof;
  double ridge_height;  ///< above z0, millimetres
};

/// Ridge along the middle of the strip at z0 + ridge, eaves on both long sides at z0 + eaves.
/// Ends are gable walls (pentagons) for Gabled, or hips when `kind` is Hipped and the strip is
/// long enough; closed strips get a ring roof (reported as Hipped).
std::optional<RoofedSolid> stripSolid(const Strip& strip, double z0, double eaves, double ridge,
                                      RoofKind kind);

/// Gabled roof over a convex footprint with at most one convex hole: the ridge is the line
/// through ridge_point along ridge_dir (unit) at z0 + ridge; the slopes descend perpendicular to
/// it and reach z0 + eaves at the footprint vertex farthest from the ridge. A hole must straddle
/// the ridge line. Walls crossed by the ridge are pentagonal gables.
std::optional<RoofedSolid> gabledSolid(const Polygon& footprint, Vec2 ridge_point, Vec2 ridge_dir,
                                       double z0, double eaves, double ridge);

/// Hipped roof over a convex footprint without holes: equal slopes rise from every edge (the
/// straight-skeleton roof), slope `slope` (rise per metre) capped so that the roof is at most
/// max_rise high.
std::optional<RoofedSolid> hippedSolid(const Ring& convex, double z0, double eaves, double slope,
                                       double max_rise);

}  // namespace urbanpvs::cities::detail
