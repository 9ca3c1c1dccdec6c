#!/usr/bin/env bash
# Installs the dependencies, builds urbanpvs (Release) and runs the main job on the bundled
# sample city (cities/sample/district.city.json): urbanpvs-preprocess computes every view
# cell's PVS, urbanpvs-inspect summarizes the file, urbanpvs-cityinfo maps the occluders.
# Outputs land in build/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh

cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j"$(nproc)" \
  --target urbanpvs-preprocess urbanpvs-inspect urbanpvs-cityinfo
mkdir -p build/demo
city=cities/sample/district.city.json
echo "== urbanpvs-preprocess $city -o build/demo/district.pvs"
build/release/preprocess/urbanpvs-preprocess "$city" -o build/demo/district.pvs \
  --report build/demo/district-report.json
echo "== urbanpvs-inspect build/demo/district.pvs"
build/release/runtime/tools/urbanpvs-inspect build/demo/district.pvs
build/release/runtime/tools/urbanpvs-inspect build/demo/district.pvs \
  --svg build/demo/district-cells.svg
echo "== urbanpvs-cityinfo $city"
build/release/geometry/urbanpvs-cityinfo "$city" --svg build/demo/district-occluders.svg
echo "== written: build/demo/district.pvs, district-report.json (settings, times, counters),"
echo "   district-cells.svg (view cells), district-occluders.svg (footprints, blocks, shrunk occluders)"
