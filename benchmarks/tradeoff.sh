#!/usr/bin/env bash
# The tightness / speed trade-off of the settings a user chooses (issue 18): bakes one city with
# the defaults and with one setting changed at a time, validates every bake, and prints one
# table row per bake: the setting, cells, bake seconds, cells/s, mean PVS, misses, and tightness
# (|PVS| / objects seen, mean over the validator's tightness viewpoints). The README's
# "Choosing the settings" table comes from it. Run by hand (minutes per bake), never by ctest:
#   benchmarks/tradeoff.sh [BUILD_DIR] [CITY] [THREADS] [VIEWPOINTS]
# Without CITY it generates the README's 1 km² benchmark city (seed 7).
set -euo pipefail
build=${1:-build/release}
city=${2:-}
threads=${3:-2}
viewpoints=${4:-2000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bake=$build/preprocess/urbanpvs-preprocess
validate=$build/preprocess/validate/urbanpvs-validate
if [ -z "$city" ]; then
  city=$work/gen1.city.json
  "$build/cities/urbanpvs-citygen" --size-km2 1 --seed 7 -o "$city" > /dev/null
fi

# One variation per line: a label and the options it adds to the defaults. The pixel follows
# epsilon (its default is the largest the coupling allows, thesis 7.2).
variations=(
  "defaults|"
  "--epsilon 0.25|--epsilon 0.25"
  "--epsilon 0.5|--epsilon 0.5"
  "--epsilon 2|--epsilon 2"
  "--max-cell-edge 9|--max-cell-edge 9"
  "--max-cell-edge 36|--max-cell-edge 36"
  "--max-map 256|--max-map 256"
  "--max-map 512|--max-map 512"
)

echo "city: $(basename "$city"), $threads threads, $viewpoints viewpoints"
echo "| setting | cells | bake s | cells/s | mean PVS | misses | tightness |"
echo "|---|---|---|---|---|---|---|"
for v in "${variations[@]}"; do
  label=${v%%|*}
  read -r -a options <<< "${v#*|}"
  "$bake" "$city" -o "$work/city.pvs" --report "$work/report.json" --quiet --threads "$threads" \
    "${options[@]}"
  read -r cells total_s cps mean_pvs < <(python3 -c "
import json; r = json.load(open('$work/report.json'))
print(r['counts']['cells'], '%.0f' % r['seconds']['total'], '%.1f' % r['cells_per_second'],
      '%.1f' % r['counts']['pvs_mean'])")
  set +e
  "$validate" "$city" "$work/city.pvs" --viewpoints "$viewpoints" \
    --tightness-viewpoints "$((viewpoints / 5))" > "$work/validate.txt" 2>&1
  set -e
  misses=$(sed -n 's/.*misses: *\([0-9]*\).*/\1/p' "$work/validate.txt" | head -n 1)
  tight=$(sed -n 's/^tightness: *\([0-9.]*\).*/\1/p' "$work/validate.txt" | head -n 1)
  echo "| $label | $cells | $total_s | $cps | $mean_pvs | ${misses:-?} | ${tight:-?} |"
done
