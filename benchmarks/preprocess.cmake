# Cull maps of one typical cell of a generated 1 km² city, per backend.
add_executable(cull_map_benchmark ${CMAKE_CURRENT_LIST_DIR}/cull_map_benchmark.cpp)
target_link_libraries(cull_map_benchmark PRIVATE urbanpvs::preprocess urbanpvs::cities
                      benchmark::benchmark urbanpvs_warnings)
