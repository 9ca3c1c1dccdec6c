#include "urbanpvs/cities/Params.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace urbanpvs::cities {

double CityParams::sideMetres() const {
  return std::sqrt(size_km2) * 1000.0;
}

void validate(const CityParams& params) {
  if (!std::isfinite(params.size_km2) || params.size_km2 < CityParams::kMinSizeKm2 ||
      params.size_km2 > CityParams::kMaxSizeKm2) {
    throw std::invalid_argument(
        "city size must be between " + std::to_string(CityParams::kMinSizeKm2) + " and " +
        std::to_string(CityParams::kMaxSizeKm2) + " km², got " + std::to_string(params.size_km2));
  }
  for (const double origin : {params.origin_x, params.origin_y}) {
    if (!std::isfinite(origin) || std::fabs(origin) > 1e7) {
      throw std::invalid_argument("origin coordinates must be finite and within ±1e7 m");
    }
  }
  if (!std::isfinite(params.hills) || params.hills < 0 || params.hills > CityParams::kMaxHills) {
    throw std::invalid_argument("hills must be between 0 and " +
                                std::to_string(CityParams::kMaxHills) + " m, got " +
                                std::to_string(params.hills));
  }
  if (params.roofs != RoofMode::Flat && params.roofs != RoofMode::Lod2) {
    throw std::invalid_argument("unknown roof mode");
  }
}

const char* toString(RoofMode mode) {
  return mode == RoofMode::Lod2 ? "lod2" : "flat";
}

CityParams sampleDistrictParams() {
  CityParams p;
  p.size_km2 = 0.25;
  p.seed = 1;
  p.roofs = RoofMode::Flat;
  return p;
}

}  // namespace urbanpvs::cities
