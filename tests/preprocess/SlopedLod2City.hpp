// SPDX-License-Identifier: GPL-3.0-or-later
// The generated LoD2 city that the preprocess tests of sloped tops share: 0.1 km², seed 5, read
// with its roof slopes (--sloped-roofs), so roof faces become occluders with sloped tops
// (RoofPlaneOccluders.hpp), most of them steep (generated pitches are 25-45°).
#pragma once

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"

namespace urbanpvs::preprocess {

inline const geometry::City& sloped_lod2_city() {
  static const geometry::City city = [] {
    cities::CityParams p;
    p.size_km2 = 0.1;
    p.seed = 5;
    p.roofs = cities::RoofMode::Lod2;
    geometry::ReadOptions read;
    read.sloped_roofs = true;
    return geometry::read_city_text(cities::cityJsonText(cities::generateCity(p)), "lod2.city.json",
                                    read);
  }();
  return city;
}

}  // namespace urbanpvs::preprocess
