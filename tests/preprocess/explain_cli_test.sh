#!/usr/bin/env bash
# urbanpvs-explain end to end on a small generated city (0.1 km², seed 3, cells in a 160 m
# square, 40 m cell edges, ε = 3 m: about 120 cells): the table, the CSV files and every exit
# code of its header.
# Usage: explain_cli_test.sh WORK_DIR PREPROCESS CITYGEN EXPLAIN
set -euo pipefail
work=$1 preprocess=$2 citygen=$3 explain=$4

rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
expect_exit() {  # CODE command...: runs it, fails unless it exits with CODE
  local want=$1 rc=0
  shift
  "$@" > out.txt 2> err.txt || rc=$?
  [ "$rc" -eq "$want" ] || { cat out.txt err.txt >&2; fail "$* exited $rc, not $want"; }
}

"$citygen" --size-km2 0.1 --seed 3 -q -o city.city.json
cat > region.geojson <<'JSON'
{"type": "Polygon", "coordinates": [[[78, 340078], [238, 340078], [238, 340238], [78, 340238], [78, 340078]]]}
JSON
"$preprocess" city.city.json --max-cell-edge 40 --epsilon 3 --region region.geojson --quiet \
  --threads 2 -o city.pvs

# Explained: a row per cause, the CSV files agree with the table, nothing else left behind.
expect_exit 0 "$explain" city.city.json city.pvs --region region.geojson --viewpoints 30 \
  --threads 2 --objects-csv objects.csv --cells-csv cells.csv
cat out.txt
for cause in seen-finer elsewhere-in-cell epsilon pixel far-field occluder-model; do
  grep -q "^| $cause | " out.txt || fail "no row for $cause"
done
grep -q "^30 viewpoints in .*misses: 0$" out.txt || fail "no summary line"
excess=$(sed -n 's/^| all | \([0-9]*\) |.*/\1/p' out.txt)
[ "$(($(wc -l < objects.csv) - 1))" -eq "$excess" ] || fail "objects.csv does not have $excess rows"
head -1 objects.csv | grep -qx "viewpoint,cell,x,y,z,object,source_id,cause" ||
  fail "objects.csv header"
head -1 cells.csv |
  grep -qx "cell,viewpoints,mean_pvs,mean_seen,seen-finer,elsewhere-in-cell,epsilon,far-field,pixel,occluder-model" ||
  fail "cells.csv header"
left=$(ls -A | grep -E '\.tmp-[0-9]+$' || true)
[ -z "$left" ] || fail "temporary files left: $left"

# Without the bake's region the settings give other cells: 4, nothing explained.
expect_exit 4 "$explain" city.city.json city.pvs --viewpoints 30
grep -Eq "^urbanpvs-explain: city.pvs: the file has [0-9]+ cells, its settings give [0-9]+ \(another region, version or city\?\)$" \
  err.txt || { cat err.txt >&2; fail "no cell-count message"; }

# A CSV file that cannot be written: 5, and no file.
expect_exit 5 "$explain" city.city.json city.pvs --region region.geojson --viewpoints 5 \
  --objects-csv missing/objects.csv
grep -q "missing/objects.csv" err.txt || { cat err.txt >&2; fail "the message does not name the file"; }
[ ! -e missing ] || fail "missing/ was created"

# Not a PVS file: 21. An option out of its limits: 2.
expect_exit 21 "$explain" city.city.json city.city.json
expect_exit 2 "$explain" city.city.json city.pvs --pixel-divisor 0
grep -qx "urbanpvs-explain: pixel divisor must be 1 .. 16" err.txt || { cat err.txt >&2; fail "usage message"; }
echo "explain CLI: all cases passed"
