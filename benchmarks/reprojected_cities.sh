#!/usr/bin/env bash
# The 3D BAG tile (EPSG:7415) rewritten in WGS84 lon/lat, Web Mercator, ETRS89 degrees and New
# York's state plane in US survey feet (benchmarks/cityjson_reproject), each baked with the
# default options and validated: the readers transform each into WGS84 lon/lat, so every row
# should give the RD original's occluders, mean PVS and tightness. Run by hand (minutes per
# row), never by ctest:
#   benchmarks/reprojected_cities.sh [BUILD_DIR] [CITIES_DIR] [VIEWPOINTS]
set -euo pipefail
build=${1:-build/release}
cities=${2:-../shared/cities}
viewpoints=${3:-300}
city=$cities/tudelft_3dbag_tile5910.city.json
[ -f "$city" ] || { echo "SKIP: $city is absent" >&2; exit 0; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| system | occluders | cells | cells/s | mean PVS | misses | tightness |"
echo "|---|---|---|---|---|---|---|"
for epsg in 7415 4326 3857 4258 2263; do
  input=$city
  if [ "$epsg" != 7415 ]; then
    input=$work/bag_$epsg.city.json
    "$build/benchmarks/cityjson_reproject" "$city" "$input" 7415 "$epsg"
  fi
  "$build/preprocess/urbanpvs-preprocess" "$input" -o "$work/bag.pvs" --threads 2 -q \
    --report "$work/report.json"
  "$build/preprocess/validate/urbanpvs-validate" "$input" "$work/bag.pvs" \
    --viewpoints "$viewpoints" > "$work/validate.txt" 2>&1 || true
  python3 - "$epsg" "$work/report.json" "$work/validate.txt" <<'PY'
import json, re, sys
epsg, report, validate = sys.argv[1:]
r = json.load(open(report))
v = open(validate).read()
misses = re.search(r"misses: (\d+)", v).group(1)
tight = re.search(r"tightness: +([\d.]+)", v).group(1)
c = r["counts"]
print(f"| EPSG:{epsg} | {c['occluders']} | {c['cells']} | {r['cells_per_second']:.1f} | "
      f"{c['pvs_mean']:.1f} | {misses} | {tight} |")
PY
done
