// SPDX-License-Identifier: GPL-3.0-or-later
// The ground under free space: where a viewer's feet are. View cells span an eye band above it
// (thesis 5.3), so the ground decides the cells' z range and the height of their samples.
#pragma once

#include <array>
#include <memory>
#include <utility>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

class GroundModel {
 public:
  enum class Source {
    Terrain,    ///< the city's TIN, interpolated linearly; outside it, its nearest point
    Buildings,  ///< inverse-distance weighting of the nearest buildings' ground_z
    Zero,       ///< no terrain and no buildings: z = 0
  };

  /// Uses the terrain when the city has one, else the buildings' ground heights.
  explicit GroundModel(const City& city);
  ~GroundModel();
  GroundModel(const GroundModel&) = delete;
  GroundModel& operator=(const GroundModel&) = delete;

  /// Ground height (absolute) at p. Continuous within the terrain; on a footprint's boundary the
  /// building's own ground_z.
  double at(Vec2 p) const;

  /// Bounds (lowest, highest) on the ground anywhere in triangle `t`, not only at its corners
  /// (thesis 5.3: a cell's top lies eye_max above the ground under every viewpoint it holds).
  /// Exact at the corners' heights on flat ground; never narrower than the ground there.
  std::pair<double, double> range_in(const std::array<Vec2, 3>& t) const;

  Source source() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace urbanpvs::geometry
