// CityJSON 2.0 output of a generated city.
#pragma once

#include <iosfwd>
#include <string>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities {

/// The city as a CityJSON 2.0 document: transform scale 0.001 with translate = the city origin,
/// integer vertices, EPSG:31256, one Building per building (LoD "1.2" solids for flat roofs,
/// "2.2" for LoD2, both with Ground/Wall/RoofSurface semantics), BuildingPart children for
/// composite buildings (whose parent Building has an empty geometry array). Attributes:
/// measuredHeight (ridge), eavesHeight, roofType ("flat roof", "gabled roof", "hipped roof"),
/// storeysAboveGround, block. One CityObject and one vertex per line. Byte-for-byte deterministic.
std::string cityJsonText(const City& city);

/// Writes cityJsonText(city) to `out`.
void writeCityJson(const City& city, std::ostream& out);

}  // namespace urbanpvs::cities
