#!/usr/bin/env bash
# Installs the dependencies, builds urbanpvs (Release) and runs the main job on the bundled
# sample city (cities/sample/district.city.json). Outputs land in build/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh

cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j"$(nproc)" --target urbanpvs-cityinfo
mkdir -p build/demo
city=cities/sample/district.city.json
echo "== urbanpvs-cityinfo $city"
build/release/geometry/urbanpvs-cityinfo "$city" --svg build/demo/district-occluders.svg
echo "== map of footprints, blocks and shrunk occluders: build/demo/district-occluders.svg"
