// SPDX-License-Identifier: GPL-3.0-or-later
// The ground truth of urbanpvs-validate: the real buildings as prisms, traced by rays. It shares
// no code with the cull-map path, so an error there cannot hide here.
//  - Blockers are the buildings' occluder prisms *before* shrinking (ground footprint up to the
//    lowest roof point, and down into the ground below it; grown by half the bake's block gap
//    tolerance, at least 1 mm, so that buildings sharing a wall, or closer than the gap the
//    bake fuses, are one solid): solid for sure, so a ray they stop is really stopped.
//  - Targets are each building's footprint up to its highest point: a ray that enters a target
//    before any blocker sees that building.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "urbanpvs/geometry/CityModel.hpp"

namespace urbanpvs::validate {

using geometry::Box2;
using geometry::Polygon;
using geometry::Vec2;

struct Point3 {
  double x = 0, y = 0, z = 0;
};

class RayScene {
 public:
  /// Blocker footprints grow by `crack` (m): buildings closer than 2·crack are one solid.
  explicit RayScene(const geometry::City& city, double crack = kSharedWall);
  RayScene(const RayScene&) = delete;  // prisms point into grown_
  RayScene& operator=(const RayScene&) = delete;

  static constexpr double kSharedWall = 1e-3;  ///< [m] least growth: closes shared walls

  /// True when the open segment p→q passes through a blocker of any object other than `skip`.
  bool blocked(const Point3& p, const Point3& q, std::uint32_t skip) const;

  /// Objects whose targets the segment p→q enters before its first blocker, appended to `seen`.
  void seen_along(const Point3& p, const Point3& q, std::vector<std::uint32_t>& seen) const;

  const Box2& bounds() const { return bounds_; }

 private:
  static constexpr double kBelowGround = -1e6;  ///< [m] where blockers end below the ground
  struct Prism {
    const Polygon* footprint;
    Box2 box;
    double zmin, zmax;
    std::uint32_t object;
    bool blocker;  // else a target
  };
  /// Entry parameter t in [0, 1] of the segment into the prism, or > 1 when it misses.
  static double entry(const Prism& prism, const Point3& p, const Point3& q);
  template <class F>
  void for_each_candidate(const Point3& p, const Point3& q, F&& f) const;

  std::deque<Polygon> grown_;  ///< blocker footprints (stable addresses)
  std::vector<Prism> prisms_;
  Box2 bounds_;
  double cell_ = 20;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> grid_;
  mutable std::vector<std::uint32_t> stamp_;
  mutable std::uint32_t query_ = 0;
};

}  // namespace urbanpvs::validate
