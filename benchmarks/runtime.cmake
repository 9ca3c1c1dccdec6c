# SPDX-License-Identifier: MIT
# Runtime benchmark (issue 6): locate + PVS iteration per query, and PVS bytes per cell, on a
# synthetic 40k-cell / 20k-building city. Included from benchmarks/CMakeLists.txt.
add_executable(runtime_benchmark
  ${CMAKE_CURRENT_LIST_DIR}/runtime_benchmark.cpp
  ${CMAKE_CURRENT_LIST_DIR}/RuntimeFileTable.cpp
  ${CMAKE_CURRENT_LIST_DIR}/MemoryLatency.cpp
  ${PROJECT_SOURCE_DIR}/tests/runtime/support/SyntheticCity.cpp)
target_include_directories(runtime_benchmark PRIVATE ${PROJECT_SOURCE_DIR}/tests/runtime/support)
target_link_libraries(runtime_benchmark PRIVATE urbanpvs_runtime benchmark::benchmark urbanpvs_warnings)
