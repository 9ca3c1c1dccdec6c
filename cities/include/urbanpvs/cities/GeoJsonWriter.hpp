// GeoJSON output of a generated city's footprints.
#pragma once

#include <iosfwd>
#include <string>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities {

/// The footprints as an RFC 7946-structured FeatureCollection in EPSG:31256 metres (named in a
/// top-level "crs" member), one Polygon feature per simple building and per part of a composite
/// building. Properties: id, block, height (the eaves height, metres: extruding a footprint to it
/// never overstates an occluder), roof:height (ridge minus eaves), roof:shape, building:levels;
/// parts also carry building:part and building (the parent id). Byte-for-byte deterministic.
std::string geoJsonText(const City& city);

/// Writes geoJsonText(city) to `out`.
void writeGeoJson(const City& city, std::ostream& out);

}  // namespace urbanpvs::cities
