// The procedural city generator (see cities/README.md for what it builds and why).
#pragma once

#include <cstddef>

#include "urbanpvs/cities/Model.hpp"
#include "urbanpvs/cities/Params.hpp"

namespace urbanpvs::cities {

/// Generates the city described by `params`. Deterministic: the same parameters give the same
/// model on every platform. Throws std::invalid_argument for out-of-range parameters.
City generateCity(const CityParams& params);

/// Number of buildings counting each part of a composite building separately plus the composite
/// itself, i.e. the number of CityJSON CityObjects the city writes to.
std::size_t cityObjectCount(const City& city);

}  // namespace urbanpvs::cities
