// SPDX-License-Identifier: MIT
#pragma once

// A synthetic but realistic bake for compression tests and the runtime benchmark: a regular
// triangle mesh of view cells over a square city, buildings scattered over it, and a visibility
// model with the statistics of real from-region PVSs — a near field whose radius varies
// smoothly over the city (open squares vs narrow streets) and is larger for taller buildings,
// plus tall landmarks visible from far away. Neighbouring cells share ~90% of their PVS.

#include <cstdint>

#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::test {

struct SyntheticCityOptions {
  double extent_m = 3000;           ///< the city is [0, extent]²
  std::uint32_t squares = 141;      ///< mesh squares per side (2 triangles each): 141 → 39,762
  std::uint32_t objects = 20000;    ///< buildings
  double near_radius_m = 135;       ///< mean near-field radius
  double landmark_fraction = 0.02;  ///< share of buildings that are landmarks
  double landmark_radius_m = 900;   ///< how far landmarks are seen
  std::uint64_t seed = 1;
};

runtime::PvsBake synthetic_city(const SyntheticCityOptions& options);

}  // namespace urbanpvs::test
