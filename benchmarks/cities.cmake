# Procedural city generator: generation + CityJSON writing for 1, 4 and 8 km².
add_executable(citygen_benchmark ${CMAKE_CURRENT_LIST_DIR}/citygen_benchmark.cpp)
target_link_libraries(citygen_benchmark PRIVATE urbanpvs::cities benchmark::benchmark urbanpvs_warnings)
