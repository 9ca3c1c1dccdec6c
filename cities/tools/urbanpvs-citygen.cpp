// urbanpvs-citygen: writes a procedural sample city as CityJSON (and optionally GeoJSON).
//
// Output goes to a temporary file first and is renamed over <path> only when complete
// (runtime::write_file_atomic), so an interrupted run never leaves a truncated city where a
// previous good one was. Exit codes: the tools' one table (urbanpvs/runtime/ExitCodes.hpp).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/cities/GeoJsonWriter.hpp"
#include "urbanpvs/runtime/ExitCodes.hpp"
#include "urbanpvs/runtime/FileIo.hpp"

namespace {

namespace fs = std::filesystem;
using urbanpvs::cities::CityParams;
using urbanpvs::cities::RoofMode;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Generates a deterministic procedural city (perimeter blocks around courtyards, solid\n"
      "blocks, parks, towers, a river) and writes it as CityJSON 2.0, optionally also as GeoJSON.\n"
      "Coordinates are EPSG:31256 (MGI / Austria GK East) metres; identical arguments give\n"
      "identical bytes on every platform."};
  CityParams params;
  double side_m = 0.0;
  std::string roofs = "flat";
  std::string cityjson_path;
  std::string geojson_path;

  auto* size_opt =
      app.add_option("--size-km2", params.size_km2,
                     "Area of the square city in km² (0.1-100; 1 km² ~ 1,000 buildings)")
          ->capture_default_str()
          ->check(CLI::Range(CityParams::kMinSizeKm2, CityParams::kMaxSizeKm2));
  app.add_option("--side-m", side_m,
                 "Side length of the square city in metres (317-10000), instead of --size-km2")
      ->check(CLI::Range(317.0, 10000.0))
      ->excludes(size_opt);
  app.add_option("--seed", params.seed, "Random seed (unsigned 64-bit integer)")
      ->capture_default_str();
  app.add_option("--roofs", roofs, "Roofs: flat (LoD1 prisms) or lod2 (gabled and hipped roofs)")
      ->capture_default_str()
      ->check(CLI::IsMember({"flat", "lod2"}));
  app.add_option("--hills", params.hills,
                 "Relief of the terrain in metres: smooth hills and valleys written as a CityJSON "
                 "TINRelief, buildings standing on them (0: flat ground, no terrain; the "
                 "--geojson footprints stay flat)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, CityParams::kMaxHills));
  app.add_option("--origin-x", params.origin_x,
                 "EPSG:31256 easting of the south-west corner, metres")
      ->capture_default_str();
  app.add_option("--origin-y", params.origin_y,
                 "EPSG:31256 northing of the south-west corner, metres")
      ->capture_default_str();
  app.add_option("-o,--output", cityjson_path, "CityJSON output file (e.g. city.city.json)")
      ->required();
  app.add_option("--geojson", geojson_path, "Also write the footprints as GeoJSON to this file");
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "Print nothing on success");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? urbanpvs::exit_code::kOk : urbanpvs::exit_code::kUsage;
  }

  try {
    if (side_m > 0.0) params.size_km2 = (side_m / 1000.0) * (side_m / 1000.0);
    params.roofs = roofs == "lod2" ? RoofMode::Lod2 : RoofMode::Flat;
    const auto start = std::chrono::steady_clock::now();
    const urbanpvs::cities::City city = urbanpvs::cities::generateCity(params);
    urbanpvs::runtime::write_file_atomic(cityjson_path, urbanpvs::cities::cityJsonText(city));
    if (!geojson_path.empty())
      urbanpvs::runtime::write_file_atomic(geojson_path, urbanpvs::cities::geoJsonText(city));
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    if (!quiet) {
      std::printf("%zu blocks, %zu buildings, %.0f m x %.0f m, written in %.2f s\n",
                  city.blocks.size(), city.buildings.size(), city.side, city.side, took.count());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "urbanpvs-citygen: error: %s\n", e.what());
    return urbanpvs::exit_code::kOutput;
  }
  return urbanpvs::exit_code::kOk;
}
