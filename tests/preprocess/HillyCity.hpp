// SPDX-License-Identifier: GPL-3.0-or-later
// Generated hilly cities for the preprocess tests of terrain occluders: seed 5, the relief
// written as a CityJSON TINRelief (CityParams::hills).
#pragma once

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"

namespace urbanpvs::preprocess {

/// A city of `km2` on hills of up to `hills` metres.
inline geometry::City generated_hilly_city(double km2, double hills) {
  cities::CityParams p;
  p.size_km2 = km2;
  p.seed = 5;
  p.hills = hills;
  return geometry::read_city_text(cities::cityJsonText(cities::generateCity(p)), "hills.city.json");
}

}  // namespace urbanpvs::preprocess
