#!/usr/bin/env bash
# Bakes the OpenStreetMap files of ../shared/cities straight from their PBF with the default
# options (issue 15's table): Helsinki with cells everywhere and on its streets, Monaco on its
# SRTM tile, Andorra on its streets and SRTM tile, Liechtenstein on its streets. One table row
# per bake: buildings, those from multipolygons, geometric repairs, buildings without height
# (objects that occlude nothing), the reader's warnings, the view cells' area and count, bake
# seconds, cells/s, peak MiB, mean PVS, culled share, and where validated (Helsinki, Monaco)
# the misses and tightness urbanpvs-validate finds. Run by hand (about 20 minutes on 2 cores),
# never by ctest:
#   benchmarks/osm_cities.sh [BUILD_DIR] [CITIES_DIR] [VIEWPOINTS]
set -euo pipefail
build=${1:-build/release}
cities=${2:-../shared/cities}
viewpoints=${3:-2000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bake=$build/preprocess/urbanpvs-preprocess
validate=$build/preprocess/validate/urbanpvs-validate

# file | view cells | DEM (or -) | validate (yes/no)
runs=(
  "Helsinki.osm.pbf|everywhere|-|yes"
  "Helsinki.osm.pbf|streets|-|yes"
  "monaco-2021.osm.pbf|everywhere|dem/N43E007.hgt|yes"
  "andorra-2013.osm.pbf|streets|dem/N42E001.hgt|no"
  "liechtenstein-2013-08-03.osm.pbf|streets|-|no"
)
rows=()
for run in "${runs[@]}"; do
  IFS='|' read -r file placement dem check <<< "$run"
  [ -f "$cities/$file" ] || { echo "SKIP: $cities/$file is absent" >&2; continue; }
  options=(--cells "$placement")
  terrain=none
  if [ "$dem" != - ]; then
    options+=(--terrain "$cities/$dem")
    terrain=$(basename "$dem")
  fi
  echo "== $file ${options[*]}" >&2
  /usr/bin/time -f '%M' -o "$work/time.txt" \
    "$bake" "$cities/$file" "${options[@]}" -o "$work/city.pvs" --report "$work/report.json" --quiet
  peak_mib=$(( $(cat "$work/time.txt") / 1024 ))
  stats=$(python3 - "$work/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
c = r["counts"]
print("%d %d %d %d %d %.3f %d %.1f %.0f %.1f %.1f" % (
    c["objects"], c["multipolygons"], len(r["repairs"]), len(r["non_occluding"]),
    len(r["warnings"]), c["cell_area_m2"] / 1e6, c["cells"], r["seconds"]["total"],
    r["cells_per_second"], c["pvs_mean"], 100 * c["fraction_culled"]))
PY
)
  read -r objects multi repairs noheight warnings area ncells total_s cps mean culled <<< "$stats"
  misses=- tight=-
  if [ "$check" = yes ]; then
    validate_options=()
    [ "$dem" != - ] && validate_options+=(--terrain "$cities/$dem")
    set +e
    "$validate" "$cities/$file" "$work/city.pvs" "${validate_options[@]}" --viewpoints "$viewpoints" \
      --seed 11 > "$work/validate.txt" 2>&1
    set -e
    misses=$(sed -n 's/.*misses: *\([0-9]*\).*/\1/p' "$work/validate.txt" | head -n 1)
    tight=$(sed -n 's/^tightness: *\([0-9.]*\).*/\1/p' "$work/validate.txt" | head -n 1)
  fi
  rows+=("| \`$file\` | $placement | $terrain | $objects | $multi | $repairs | $noheight | $warnings | $area | $ncells | $total_s | $cps | $peak_mib | $mean | $culled % | ${misses:-?} | ${tight:-?} |")
done
echo "viewpoints per validated bake: $viewpoints"
echo "| file | cells | terrain | buildings | multipolygons | repairs | no height | OSM warnings | cell area km² | cells | bake s | cells/s | peak MiB | mean PVS | culled | misses | tightness |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
