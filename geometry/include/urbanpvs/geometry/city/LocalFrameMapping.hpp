// SPDX-License-Identifier: GPL-3.0-or-later
// Maps input coordinates into the local metric frame every stage works in. Projected inputs are
// shifted to an origin near the data so floats in the cull-map renderer keep millimetres;
// WGS84 lon/lat inputs go through GeographicLib's local east-north-up projection.
#pragma once

#include <array>
#include <memory>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// Picks the local frame for input whose coordinates span `input_bounds`: for projected input the
/// origin is the lower-left corner rounded down to whole metres (exactly representable, so the
/// offset is lossless); for geographic input the centre of the box at height 0.
LocalFrame choose_local_frame(LocalFrame::Kind kind, std::string crs, const Box2& input_bounds);

class LocalFrameMapping {
 public:
  explicit LocalFrameMapping(const LocalFrame& frame);
  ~LocalFrameMapping();
  LocalFrameMapping(const LocalFrameMapping&) = delete;
  LocalFrameMapping& operator=(const LocalFrameMapping&) = delete;

  /// Input (x, y, z) -> local. For geographic input x = lon, y = lat (degrees), z = height; the
  /// local x, y are east and north of the point's foot on the ellipsoid, and the local z keeps
  /// the input height (the earth's curvature, 8 cm at 1 km, is ignored), so verticals stay
  /// vertical.
  Vec3 to_local(double x, double y, double z) const;
  /// Local -> input coordinates (inverse of to_local).
  Vec3 to_input(double x, double y, double z) const;

  const LocalFrame& frame() const { return frame_; }

 private:
  struct Geodesy;
  LocalFrame frame_;
  std::unique_ptr<Geodesy> geodesy_;
};

}  // namespace urbanpvs::geometry
