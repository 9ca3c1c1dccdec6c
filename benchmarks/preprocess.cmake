# Cull maps of one typical cell of a generated 1 km² city, per backend.
add_executable(cull_map_benchmark ${CMAKE_CURRENT_LIST_DIR}/cull_map_benchmark.cpp)
target_link_libraries(cull_map_benchmark PRIVATE urbanpvs::preprocess urbanpvs::cities
                      benchmark::benchmark urbanpvs_warnings)

# Brute force against the hierarchical test (issue 5): cells/s, PVS comparison, counters.
add_executable(hierarchical_benchmark ${CMAKE_CURRENT_LIST_DIR}/hierarchical_benchmark.cpp)
target_link_libraries(hierarchical_benchmark PRIVATE urbanpvs::preprocess urbanpvs::cities
                      urbanpvs_warnings)

# The whole urbanpvs-preprocess run on generated 1, 4 and 8 km² cities and on every real city of
# URBANPVS_SHARED_CITIES (issues 7 and 13): cells/s, time per cell, peak memory, mean PVS, the
# PVS change against an earlier run. A plain program; see its --help.
add_executable(preprocess_benchmark ${CMAKE_CURRENT_LIST_DIR}/preprocess_benchmark.cpp)
target_link_libraries(preprocess_benchmark PRIVATE urbanpvs::bake urbanpvs::cities
                      nlohmann_json::nlohmann_json CLI11::CLI11 urbanpvs_warnings)
target_compile_definitions(preprocess_benchmark PRIVATE
                           URBANPVS_SHARED_CITIES="${PROJECT_SOURCE_DIR}/../shared/cities")
