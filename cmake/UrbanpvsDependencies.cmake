# The heavy dependencies of the offline builder. All come from Debian 12's packages, installed by
# scripts/install-deps.sh. See README.md ("Dependencies") for why each one is here.
find_package(CGAL 5.5 REQUIRED)                     # CDT, mesher, straight skeleton, Boolean ops
find_package(nlohmann_json 3.10 REQUIRED)           # CityJSON and GeoJSON input, reports
find_package(CLI11 REQUIRED)                        # command lines
find_package(PkgConfig REQUIRED)
pkg_check_modules(GeographicLib REQUIRED IMPORTED_TARGET geographiclib)  # WGS84 -> local metric frame
pkg_check_modules(OSMesa REQUIRED IMPORTED_TARGET osmesa)               # off-screen cull maps
find_package(glm REQUIRED)                          # the 2D and 3D vector types
find_package(GDAL 3.6 CONFIG REQUIRED)              # DEM rasters for --terrain (GeoTIFF, SRTM)

# OpenStreetMap input (header-only libosmium; PBF needs zlib and threads, XML expat, .bz2 bzip2).
find_path(OSMIUM_INCLUDE_DIR osmium/osm.hpp REQUIRED)
find_package(ZLIB REQUIRED)
find_package(EXPAT REQUIRED)
find_package(BZip2 REQUIRED)
find_package(Threads REQUIRED)
add_library(Osmium::Osmium INTERFACE IMPORTED)
target_include_directories(Osmium::Osmium SYSTEM INTERFACE ${OSMIUM_INCLUDE_DIR})
target_link_libraries(Osmium::Osmium INTERFACE ZLIB::ZLIB EXPAT::EXPAT BZip2::BZip2 Threads::Threads)

# TetGen (libtet1.5-dev) has neither a CMake config nor pkg-config: its header and library.
if(URBANPVS_TETGEN)
  find_path(TETGEN_INCLUDE_DIR tetgen.h REQUIRED)
  find_library(TETGEN_LIBRARY tet REQUIRED)
  add_library(TetGen::TetGen UNKNOWN IMPORTED)
  set_target_properties(TetGen::TetGen PROPERTIES IMPORTED_LOCATION ${TETGEN_LIBRARY}
                        INTERFACE_INCLUDE_DIRECTORIES ${TETGEN_INCLUDE_DIR})
endif()
