#!/usr/bin/env bash
# A real city of ../shared/cities baked with the default options, then checked by
# urbanpvs-validate against the input's own surfaces (issue 11: every real city bakes with the
# defaults, and the PVS stays conservative). Skips, saying so, when the city is absent.
# Usage: real_city_test.sh CITY WORK_DIR PREPROCESS VALIDATE VIEWPOINTS
set -euo pipefail
city=$1 work=$2 preprocess=$3 validate=$4 viewpoints=$5
if [ ! -f "$city" ]; then
  echo "SKIP: $city is absent (real city extracts live in ../shared/cities)"
  exit 0
fi
rm -rf "$work"
mkdir -p "$work"
"$preprocess" "$city" -o "$work/city.pvs" --report "$work/report.json" 2> "$work/summary.txt" || {
  cat "$work/summary.txt" >&2
  echo "FAIL: the default bake of $city failed" >&2
  exit 1
}
grep -E '^(cells|input|PVS|time|memory):' "$work/summary.txt"
"$validate" "$city" "$work/city.pvs" --viewpoints "$viewpoints" --seed 11 || {
  echo "FAIL: urbanpvs-validate found misses in the default bake of $city" >&2
  exit 1
}
rm -rf "$work"
echo "PASS: $(basename "$city")"
