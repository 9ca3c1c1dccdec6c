#!/usr/bin/env bash
# Installs every system package urbanpvs needs to build, test and benchmark on Debian 12.
# Nothing is ever installed by hand: CI and the README's quick start both call this script.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config clang clang-format
  # the sanitizer pass of scripts/test.sh: clang's runtime for its sanitizers and libFuzzer, and
  # lld, which links the test executables in less than half of GNU ld's time
  libclang-rt-14-dev lld
  # geometry: triangulation, straight skeleton, Boolean operations (GPL parts of CGAL)
  libcgal-dev libgmp-dev libmpfr-dev
  # the 3D shrinking route (thesis 7.3.1): TetGen, AGPL, linked only with URBANPVS_TETGEN=ON
  libtet1.5-dev
  # OpenStreetMap input (PBF and XML)
  libosmium2-dev
  # CityGML input (streaming XML parser; libosmium's XML reader uses it too)
  libexpat1-dev
  # terrain: DEMs (GeoTIFF, SRTM .hgt) read and reprojected with GDAL (--terrain)
  libgdal-dev
  # coordinates: WGS84 lon/lat -> local metric frame
  libgeographiclib-dev
  # the 2D and 3D vector types of every builder stage
  libglm-dev
  # off-screen OpenGL for cull maps (llvmpipe)
  libosmesa6-dev
  # baking across machines: mpirun -n N urbanpvs-preprocess (and its test)
  libopenmpi-dev openmpi-bin
  # JSON input, command lines, tests, benchmarks
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
