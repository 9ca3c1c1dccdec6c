// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-validate's core: checks a PVS file against ray casting in the real city. From random
// viewpoints inside the cells (on the top face and inside the prism) it casts rays towards the
// surface of every object missing from the cell's PVS: an unblocked ray is a *miss*, the worst
// bug a PVS can have. It also measures tightness: |PVS| over the number of objects actually
// seen (point rays to every object plus a cube map of directions).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "urbanpvs/geometry/CityModel.hpp"
#include "urbanpvs/runtime/pvs_file.hpp"
#include "urbanpvs/validate/RayScene.hpp"

namespace urbanpvs::validate {

struct ValidationOptions {
  std::size_t viewpoints = 2000;           ///< viewpoints checked for misses
  std::size_t tightness_viewpoints = 200;  ///< of those, the first n also measure tightness
  int cube_resolution = 16;                ///< rays per cube face side for tightness
  double point_spacing = 2.0;              ///< [m] between target points along walls
  std::uint64_t seed = 1;
};

struct Miss {
  std::uint32_t cell = 0;
  Point3 viewpoint;
  std::uint32_t object = 0;
  std::string object_id;
  Point3 target;  ///< the point of the object the ray reached
};

struct ValidationReport {
  std::size_t viewpoints = 0;
  std::size_t rays = 0;
  std::vector<Miss> misses;
  std::size_t pvs_total = 0;   ///< summed |PVS| over the tightness viewpoints
  std::size_t seen_total = 0;  ///< summed number of objects seen from them
  double tightness() const { return seen_total ? double(pvs_total) / double(seen_total) : 0; }
};

/// Throws std::runtime_error when the file does not belong to the city (object count or ids
/// differ). `city` must be read with the same options as for the bake.
ValidationReport validate(const geometry::City& city, const runtime::PvsFile& pvs,
                          const ValidationOptions& options);

}  // namespace urbanpvs::validate
