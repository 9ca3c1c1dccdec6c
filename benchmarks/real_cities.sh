#!/usr/bin/env bash
# Bakes every real city of ../shared/cities (CityJSON and GeoJSON; the OSM PBF files wait for an
# OSM reader) with the default options and validates each bake, then prints one table row per
# city: buildings, geometric repairs, objects that occlude nothing, view cells, cells per km² of
# free space, meshing seconds and peak MiB (urbanpvs-cells), bake seconds and cells/s
# (urbanpvs-preprocess, all cores), mean PVS, and the misses and tightness urbanpvs-validate
# finds. Run by hand (minutes per city), never by ctest:
#   benchmarks/real_cities.sh [BUILD_DIR] [CITIES_DIR] [VIEWPOINTS]
set -euo pipefail
build=${1:-build/release}
cities=${2:-../shared/cities}
viewpoints=${3:-2000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
info=$build/geometry/urbanpvs-cityinfo
cells=$build/geometry/urbanpvs-cells
bake=$build/preprocess/urbanpvs-preprocess
validate=$build/preprocess/validate/urbanpvs-validate

rows=()
for city in "$cities"/*.city.json "$cities"/*.geojson; do
  [ -f "$city" ] || continue
  name=$(basename "$city")
  echo "== $name" >&2
  "$info" "$city" > "$work/info.txt"
  objects=$(sed -n 's/^objects: *\([0-9]*\).*/\1/p' "$work/info.txt")
  repairs=$(sed -n 's/^repairs: *\([0-9]*\) geometric repairs, \([0-9]*\) objects.*/\1/p' "$work/info.txt")
  nonocc=$(sed -n 's/^repairs: *\([0-9]*\) geometric repairs, \([0-9]*\) objects.*/\2/p' "$work/info.txt")
  /usr/bin/time -f '%e %M' -o "$work/time.txt" "$cells" "$city" > "$work/cells.txt"
  read -r mesh_s mesh_kb < "$work/time.txt"
  ncells=$(sed -n 's/^cells: *\([0-9]*\).*/\1/p' "$work/cells.txt")
  free=$(sed -n 's/^free space: *\([0-9.]*\) m2.*/\1/p' "$work/cells.txt")
  "$bake" "$city" -o "$work/city.pvs" --report "$work/report.json" --quiet
  bake_s=$(python3 -c "import json;r=json.load(open('$work/report.json'));print('%.0f %.1f %.1f' % (r['seconds']['total'], r['cells_per_second'], r['counts']['pvs_mean']))")
  read -r total_s cps mean_pvs <<< "$bake_s"
  set +e
  "$validate" "$city" "$work/city.pvs" --viewpoints "$viewpoints" > "$work/validate.txt" 2>&1
  set -e
  misses=$(sed -n 's/.*misses: *\([0-9]*\).*/\1/p' "$work/validate.txt" | head -n 1)
  tight=$(sed -n 's/^tightness: *\([0-9.]*\).*/\1/p' "$work/validate.txt" | head -n 1)
  density=$(python3 -c "print('%.0f' % ($ncells / ($free / 1e6)))")
  mib=$(python3 -c "print('%.0f' % ($mesh_kb / 1024))")
  rows+=("| $name | $objects | $repairs | $nonocc | $ncells | $density | $mesh_s | $mib | $total_s | $cps | $mean_pvs | ${misses:-?} | ${tight:-?} |")
done
echo "viewpoints per city: $viewpoints"
echo "| city | buildings | repairs | non-occluding | cells | cells/km² free | meshing s | meshing MiB | bake s | cells/s | mean PVS | misses | tightness |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
