# Geometry stage: view-cell subdivision (thesis 5.3) of generated cities of 1, 4 and 8 km².
add_executable(view_cells_benchmark ${CMAKE_CURRENT_LIST_DIR}/view_cells_benchmark.cpp)
target_link_libraries(view_cells_benchmark PRIVATE urbanpvs::geometry urbanpvs::cities
                      benchmark::benchmark urbanpvs_warnings)

# Input in other reference systems: a CityJSON city rewritten in lon/lat, Web Mercator or feet
# (benchmarks/reprojected_cities.sh bakes and validates each).
add_executable(cityjson_reproject ${CMAKE_CURRENT_LIST_DIR}/cityjson_reproject.cpp)
target_link_libraries(cityjson_reproject PRIVATE GDAL::GDAL nlohmann_json::nlohmann_json
                      urbanpvs_warnings)
