// The street network: a warped, jittered grid of block corners with streets of varying width,
// crossed by one straight river. Its output is the list of building lots (blocks).
#pragma once

#include <cstdint>
#include <vector>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities::detail {

struct StreetNetwork {
  /// Convex counter-clockwise lots (the land between streets), snapped to millimetres, in
  /// row-major grid order (the order of block ids).
  std::vector<Ring> lots;
  OpenStrip river;
};

/// Lays out the streets of a square city of `side` metres.
StreetNetwork layoutStreets(double side, std::uint64_t seed);

}  // namespace urbanpvs::cities::detail
