#!/usr/bin/env bash
# Installs the dependencies, builds urbanpvs (Release, warnings as errors) and runs the whole test
# suite; then builds again with clang and -fsanitize=address,undefined, runs the suite once more
# (the .pvs loader's fuzzer included), and builds the runtime alone.
# This is the README's test command and what CI runs (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh

jobs=$(nproc)
# lld links the ~40 test and tool executables of each build in well under half of GNU ld's time.
lld=(-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld)
echo "== Formatting (clang-format --dry-run --Werror, the checked-in .clang-format)"
git ls-files '*.cpp' '*.hpp' '*.h' '*.c' | xargs clang-format --dry-run --Werror

echo "== Release build, GCC (warnings are errors)"
# With TetGen (AGPL), so that the 3D shrinking route is built and tested too. Without
# link-time optimisation: it would redo the optimisation at each of those links (and lld cannot
# link GCC's LTO objects); the same sources give the same PVS with it (README, "Link-time
# optimisation").
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DURBANPVS_WERROR=ON \
  -DURBANPVS_TETGEN=ON -DURBANPVS_LTO=OFF "${lld[@]}"
cmake --build build/release -j"$jobs"
# Tests labelled "heavy" (default bakes of the two largest real cities, 4-7 min each) only on
# request: CI's budget is 30 minutes on 2 cores.
heavy=(-LE heavy)
if [ "${URBANPVS_HEAVY_TESTS:-0}" = 1 ]; then heavy=(); fi
ctest --test-dir build/release --output-on-failure -j"$jobs" --timeout 900 "${heavy[@]}"

if [ "${URBANPVS_SKIP_SANITIZERS:-0}" != 1 ]; then
  # Heavy checks run once, in the Release pass: tests labelled "slow" (the ray-cast validation
  # of whole bakes, 2,000 viewpoints each), the whole-city comparisons below (brute force
  # against the hierarchical test, real cities meshed and fused) and the tests that read the
  # 3D BAG tile (80-95 s each under the sanitizers). Under the sanitizers they would take most
  # of CI's time and reach no code that the smaller tests of the same stages miss (the reader
  # fuzz replay, the random roofs); the urbanpvs-preprocess end-to-end tests still bake and
  # validate under them.
  release_only='^(ViewCells\.(Helsinki|TuDelft3dBagTile|GeneratedOneKm2TwoSeeds)'
  release_only+='|Blocks\.(BundledSampleCity|DelftCity|HelsinkiCity)'
  release_only+='|Hierarchical\..*BruteForce.*|geometry_cli_(delft|helsinki_default_height)'
  release_only+='|CityJsonSequence\.TuDelft3dBagTileReadsAsItsFile'
  release_only+='|CityGml\.TuDelft3dBagTileReadsAsItsCityJson'
  release_only+='|RepairReading\.RealTileWithOneBrokenRingReadsWithTheDefaults'
  release_only+='|RoofPlaneOccluders\.NeverAboveTheErodedRoofOnTheBagTile'
  # OpenMPI's own allocations at MPI_Init are not ours to fix, and LeakSanitizer reports them.
  release_only+='|preprocess_mpi_bake)$'
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build, clang (warnings are errors)"
  # clang: a second compiler's warnings, 40 % less compile time than GCC with the sanitizers
  # on CGAL's templates, and libFuzzer: ctest's runtime.fuzz_loader fuzzes the .pvs loader for
  # a bounded time (20 s; the seed corpus is tests/runtime/fuzz/corpus) under ASan + UBSan.
  # runtime/README.md says how to fuzz for longer. -O1 -g1: line tables for the reports. Its own
  # folder: CMake keeps the compiler of a folder configured before (by GCC, until 2026-12-05).
  CC=clang CXX=clang++ cmake -S . -B build/asan-clang -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DURBANPVS_WERROR=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DURBANPVS_SANITIZE=ON \
    -DURBANPVS_TETGEN=ON -DURBANPVS_BUILD_BENCHMARKS=OFF "${lld[@]}"
  cmake --build build/asan-clang -j"$jobs"
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions="$PWD/tests/lsan.supp" \
    ctest --test-dir build/asan-clang --output-on-failure -j"$jobs" --timeout 1800 -LE slow \
    -E "$release_only"
fi

echo "== The runtime alone (URBANPVS_RUNTIME_ONLY: C++17, no dependencies), clang"
# What engines vendor must build with nothing but a C++17 compiler.
CC=clang CXX=clang++ cmake -S . -B build/runtime-only -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DURBANPVS_RUNTIME_ONLY=ON -DURBANPVS_WERROR=ON -DURBANPVS_BUILD_TESTS=OFF "${lld[@]}"
cmake --build build/runtime-only -j"$jobs"
