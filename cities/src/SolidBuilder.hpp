// Assembles a closed solid from faces given as 3D points, sharing vertices by exact millimetre
// position. Roof constructions build every face from the same snapped points, so shared edges of
// adjacent faces end up with identical vertex indices; isClosed() checks that they did.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities::detail {

class SolidBuilder {
 public:
  /// Index of the vertex at (p, z) rounded to millimetres, added if new.
  std::uint32_t vertex(Vec2 p, double z);

  /// Adds a face from rings of points (first outer, then holes). Consecutive duplicate points
  /// are merged; a degenerate outer ring drops the face.
  void addFace(SurfaceType type, const std::vector<std::vector<Vec3>>& rings);

  /// The vertical wall under the edge a -> b of a footprint ring (interior to the left), from
  /// ground z0 up to `top`, the roof line over the edge from above a to above b inclusive.
  void addWall(Vec2 a, Vec2 b, double z0, const std::vector<Vec3>& top);

  /// True when every directed edge occurs exactly once and its reverse exactly once: a closed,
  /// consistently oriented 2-manifold.
  bool isClosed() const;

  Solid release();

 private:
  std::vector<Vec3> vertices_;
  std::map<std::array<std::int64_t, 3>, std::uint32_t> index_;
  std::vector<Face> faces_;
};

/// The ground face of a footprint: its rings reversed so that the face looks down (outwards).
void addGround(SolidBuilder& builder, const Polygon& footprint, double z0);

}  // namespace urbanpvs::cities::detail
