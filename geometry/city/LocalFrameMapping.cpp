// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>

namespace urbanpvs::geometry {

struct LocalFrameMapping::Geodesy {
  GeographicLib::LocalCartesian enu;
};

LocalFrame choose_local_frame(LocalFrame::Kind kind, std::string crs, const Box2& b) {
  LocalFrame f;
  f.kind = kind;
  f.crs = std::move(crs);
  if (kind == LocalFrame::Kind::Projected) {
    f.origin = {std::floor(b.min.x), std::floor(b.min.y), 0.0};
  } else {
    f.origin_lon = 0.5 * (b.min.x + b.max.x);
    f.origin_lat = 0.5 * (b.min.y + b.max.y);
    f.origin_h = 0;
  }
  return f;
}

LocalFrameMapping::LocalFrameMapping(const LocalFrame& frame) : frame_(frame) {
  if (frame.kind == LocalFrame::Kind::Geographic)
    geodesy_ = std::make_unique<Geodesy>(
        Geodesy{GeographicLib::LocalCartesian(frame.origin_lat, frame.origin_lon, frame.origin_h)});
}

LocalFrameMapping::~LocalFrameMapping() = default;

Vec3 LocalFrameMapping::to_local(double x, double y, double z) const {
  if (!geodesy_) return {x - frame_.origin[0], y - frame_.origin[1], z - frame_.origin[2]};
  // East and north of the point's foot on the ellipsoid, not of the point itself: in a tangent
  // plane the plumb lines of points d apart diverge by d/R, so a 40 m wall 300 m from the
  // origin would lean 2 mm outwards, and every vertical wall of a 3D model would become a
  // sliver of roof in plan. The local frame is flat with z the input's height, so a vertical
  // stays vertical (PvsFile::geodetic_to_local maps the same way).
  double e = 0, n = 0, u = 0;
  geodesy_->enu.Forward(y, x, 0, e, n, u);
  return {e, n, z};
}

Vec3 LocalFrameMapping::to_input(double x, double y, double z) const {
  if (!geodesy_) return {x + frame_.origin[0], y + frame_.origin[1], z + frame_.origin[2]};
  // Invert the horizontal part at the ellipsoid, which lies `drop` below the tangent plane.
  double lat = 0, lon = 0, h = 0;
  const double r = std::hypot(x, y);
  const double drop = r * r / (2 * 6371000.0);
  geodesy_->enu.Reverse(x, y, -drop, lat, lon, h);
  return {lon, lat, z};
}

}  // namespace urbanpvs::geometry
