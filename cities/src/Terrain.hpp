// Hills for test cities (CityParams::hills): a smooth relief that the writers give as a CityJSON
// TINRelief and that every building stands on, so the terrain route of the bake (cells on the
// ground, the validator's earth) has generated data of any size to be checked on.
#pragma once

#include <cstdint>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities::detail {

/// A relief over the city square and kTerrainMargin around it: a sum of smooth polynomial bumps
/// (hills and hollows, 120-350 m across), scaled to span exactly `hills` metres, lowest 0.
Terrain makeTerrain(double side, std::uint64_t seed, double hills);

/// Sets each building's ground_z to the lowest terrain node of the grid squares under its
/// footprint's box (so its floor never stands above the TIN anywhere under it) and raises its
/// solids by that much.
void standOnTerrain(City& city);

}  // namespace urbanpvs::cities::detail
