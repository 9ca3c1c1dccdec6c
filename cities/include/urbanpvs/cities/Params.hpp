// Parameters of the procedural city generator.
#pragma once

#include <cstdint>
#include <string>

namespace urbanpvs::cities {

/// Which roofs the generated buildings carry.
enum class RoofMode : std::uint8_t {
  Flat,  ///< LoD1: every building a prism (footprint extruded to its eaves height).
  Lod2,  ///< LoD2: gabled and hipped roofs (ridge above eaves); towers and podiums stay flat.
};

/// Everything that determines a generated city. Identical parameters give identical output bytes.
struct CityParams {
  /// Area of the (square) city in km². Range [kMinSizeKm2, kMaxSizeKm2]. 1 km² holds roughly a
  /// thousand buildings in ~250 blocks; 8 km² is the scale of Wonka's Vienna model (~2,000 blocks).
  double size_km2 = 1.0;
  /// Seed of every random choice. Any value is valid.
  std::uint64_t seed = 1;
  /// Flat (LoD1) or pitched (LoD2) roofs.
  RoofMode roofs = RoofMode::Flat;
  /// Relief of the terrain (m): 0 keeps the ground flat at z = 0 (and writes no terrain);
  /// above 0, smooth hills and valleys of up to about this height difference, written as a
  /// CityJSON TINRelief, with every building standing on it. Range [0, kMaxHills].
  double hills = 0.0;
  /// EPSG:31256 (MGI / Austria GK East) easting of the city's south-west corner, metres. The
  /// default puts the city near Vienna's centre. Rounded to millimetres. Range ±1e7.
  double origin_x = 0.0;
  /// EPSG:31256 northing of the city's south-west corner, metres. Rounded to millimetres.
  double origin_y = 340000.0;

  // Below 0.1 km² (316 m side) the river, up to ~110 m wide, would leave little city.
  static constexpr double kMinSizeKm2 = 0.1;
  static constexpr double kMaxSizeKm2 = 100.0;
  static constexpr double kMaxHills = 300.0;

  /// Side length of the square city in metres (sqrt(size_km2) * 1000).
  double sideMetres() const;
};

/// Throws std::invalid_argument with a readable message when a parameter is out of range.
void validate(const CityParams& params);

/// "flat" or "lod2".
const char* toString(RoofMode mode);

/// The parameters of the bundled sample city (cities/sample/): 0.25 km², seed 1, flat roofs.
CityParams sampleDistrictParams();

}  // namespace urbanpvs::cities
