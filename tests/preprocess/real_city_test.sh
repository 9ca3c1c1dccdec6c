#!/usr/bin/env bash
# A real city of ../shared/cities baked with the default options, then checked by
# urbanpvs-validate against the input's own surfaces (issue 11: every real city bakes with the
# defaults, and the PVS stays conservative). Skips, saying so, when the city is absent.
# Usage: real_city_test.sh CITY WORK_DIR PREPROCESS VALIDATE VIEWPOINTS [OPTION...]
# The OPTIONs (e.g. --terrain DEM --cells streets) go to the bake; the validator, which reads
# the city too, gets the --terrain among them. A --terrain file must exist as well.
set -euo pipefail
city=$1 work=$2 preprocess=$3 validate=$4 viewpoints=$5
shift 5
options=("$@")
if [ ! -f "$city" ]; then
  echo "SKIP: $city is absent (real city extracts live in ../shared/cities)"
  exit 0
fi
reading=()
for ((i = 0; i + 1 < ${#options[@]}; ++i)); do
  if [ "${options[i]}" = --terrain ]; then
    if [ ! -f "${options[i + 1]}" ]; then
      echo "SKIP: ${options[i + 1]} is absent (the DEM tiles live in ../shared/cities/dem)"
      exit 0
    fi
    reading+=(--terrain "${options[i + 1]}")
  fi
done
rm -rf "$work"
mkdir -p "$work"
"$preprocess" "$city" "${options[@]}" -o "$work/city.pvs" --report "$work/report.json" 2> "$work/summary.txt" || {
  cat "$work/summary.txt" >&2
  echo "FAIL: the default bake of $city failed" >&2
  exit 1
}
grep -E '^(cells|input|terrain|PVS|time|memory):' "$work/summary.txt"
"$validate" "$city" "${reading[@]}" "$work/city.pvs" --viewpoints "$viewpoints" --seed 11 || {
  echo "FAIL: urbanpvs-validate found misses in the default bake of $city" >&2
  exit 1
}
rm -rf "$work"
echo "PASS: $(basename "$city")"
