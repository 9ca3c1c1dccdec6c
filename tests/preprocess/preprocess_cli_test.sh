#!/usr/bin/env bash
# Integration tests of urbanpvs-preprocess on a small generated city (0.1 km², seed 3, cells only
# in a 160 m square, 40 m cell edges, ε = 3 m: about 120 cells, a bake of 1-2 s), one case per
# ctest test:
#   threads   1 and 2 threads give byte-identical files; report, metadata, no leftovers; the
#             ray-cast validator finds no miss
#   resume    kill -9 at several points, then --resume (with varying thread counts) gives the
#             byte-identical file
#   torn      the same after a torn last record and after a garbage tail; --resume without a
#             journal simply bakes
#   mismatch  a journal of other settings (or not a journal) is refused, exit 2, and kept
#   failures  unwritable output/report, bad input (JSON, CityGML, units), bad options: documented
#             exit code, no output
#   config    --config settings apply, the command line wins
#   help      --help lists every option
#   repairs   a broken ring is repaired and a building without height kept as an object that
#             occludes nothing: listed in the summary and the report, present in the file
#   payloads  --payload carries a property into the file (2.1) as each object's payload
#   citygml   a CityGML district bakes with the defaults and validates with no miss
#   terrain   --terrain DEM (an Esri ASCII grid of a slope): buildings and cells stand on it,
#             --terrain-planes makes it occlude,
#             the validator finds no miss; bad rasters exit 17; --cells FILE is --region FILE
# Usage: preprocess_cli_test.sh CASE WORK_DIR PREPROCESS CITYGEN VALIDATE INSPECT BAD_INPUT_DIR
set -euo pipefail
case_name=$1 work=$2 preprocess=$3 citygen=$4 validate=$5 inspect=$6 bad=$7

rm -rf "$work"
mkdir -p "$work"
cd "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }
same() { cmp -s "$1" "$2" || fail "$1 and $2 differ"; }
absent() { for f in "$@"; do [ ! -e "$f" ] || fail "$f was left behind"; done; }
no_temporaries() {
  local left
  left=$(ls -A | grep -E '\.tmp-[0-9]+$|\.journal\.new$' || true)
  [ -z "$left" ] || fail "temporary files left: $left"
}
now_ms() { date +%s%3N; }

"$citygen" --size-km2 0.1 --seed 3 -q -o city.city.json
# The city spans (0, 340000)..(316, 340316) in EPSG:31256; cells only in its middle.
cat > region.geojson <<'JSON'
{"type": "Polygon", "coordinates": [[[78, 340078], [238, 340078], [238, 340238], [78, 340238], [78, 340078]]]}
JSON
bake=(city.city.json --max-cell-edge 40 --epsilon 3 --region region.geojson --quiet)

# A reference file; sets ref_ms to how long it took.
make_reference() {
  local start
  start=$(now_ms)
  "$preprocess" "${bake[@]}" --threads 2 -o ref.pvs
  ref_ms=$(( $(now_ms) - start ))
  echo "reference bake: ${ref_ms} ms"
  absent ref.pvs.journal
}

# Starts a bake of OUT in the background and kills it with SIGKILL after MS milliseconds, or
# once its journal holds a record when MS is "record". Sets killed=1 when it was still running.
bake_and_kill() {
  local out=$1 when=$2 threads=$3 pid
  "$preprocess" "${bake[@]}" --threads "$threads" -o "$out" &
  pid=$!
  if [ "$when" = record ]; then
    # The header is 40 bytes; anything beyond is at least part of the first record.
    for _ in $(seq 1 6000); do
      [ "$(stat -c %s "$out.journal" 2>/dev/null || echo 0)" -gt 40 ] && break
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.01
    done
  else
    sleep "$(awk -v ms="$when" 'BEGIN { printf "%.3f", ms / 1000 }')"
  fi
  killed=0
  if kill -9 "$pid" 2>/dev/null; then killed=1; fi
  wait "$pid" 2>/dev/null || true
}

# Three buildings in EPSG:3067, two with a "tile" property (a string and a number).
write_tiles() {
  cat > tiles.geojson <<'JSON'
{"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:3067"}},
 "features": [
  {"type": "Feature", "id": "a", "properties": {"building": "yes", "height": 12, "tile": "t/0/1"},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [30, 0], [30, 20], [0, 20], [0, 0]]]}},
  {"type": "Feature", "id": "b", "properties": {"building": "yes", "height": 9, "tile": 42},
   "geometry": {"type": "Polygon", "coordinates": [[[60, 0], [70, 0], [70, 10], [60, 10], [60, 0]]]}},
  {"type": "Feature", "id": "c", "properties": {"building": "yes", "height": 9},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 60], [20, 60], [20, 75], [0, 75], [0, 60]]]}}
 ]}
JSON
}

case $case_name in
threads)
  "$preprocess" "${bake[@]}" --threads 1 -o one.pvs --report one.json
  "$preprocess" "${bake[@]}" --threads 2 -o two.pvs --report two.json
  same one.pvs two.pvs
  absent one.pvs.journal two.pvs.journal
  no_temporaries
  for key in '"input_hash"' '"settings"' '"counts"' '"seconds"' '"visibility"' '"counters"' \
             '"early_breaks"' '"peak_memory_bytes"' '"fraction_culled"' '"cells_computed"'; do
    grep -q "$key" one.json || fail "report lacks $key"
  done
  grep -q '"threads": 2' two.json || fail "report lacks the thread count"
  "$inspect" one.pvs > summary.txt
  grep -q 'property:    max_cell_edge_m = 40' summary.txt || fail "settings not in the metadata"
  grep -q 'property:    method = hierarchical' summary.txt || fail "method not in the metadata"
  grep -q 'property:    region = region.geojson' summary.txt || fail "region not in the metadata"
  "$validate" city.city.json one.pvs --viewpoints 400 --tightness-viewpoints 50 ||
    fail "urbanpvs-validate found misses (or failed)"
  # Per-cell tightness: a summary line and one CSV row per cell drawn, each PVS as the file's.
  "$validate" city.city.json one.pvs --viewpoints 0 --tightness-cells 12 \
    --viewpoints-per-cell 4 --cells-csv cells.csv > cells.txt || fail "per-cell validation failed"
  grep -q '^cell tightness: mean .* cells x 4 viewpoints' cells.txt ||
    fail "no per-cell summary: $(cat cells.txt)"
  [ "$(head -1 cells.csv)" = "cell,pvs,seen,tightness" ] || fail "CSV header: $(head -1 cells.csv)"
  [ "$(wc -l < cells.csv)" -eq 13 ] || fail "CSV rows: $(cat cells.csv)"
  while IFS=, read -r cell pvs seen ratio; do
    [ "$cell" = cell ] && continue
    "$inspect" one.pvs --cell "$cell" > cell.txt
    grep -q "^  pvs: $pvs of " cell.txt ||
      fail "cell $cell: the CSV says $pvs objects, inspect says $(cat cell.txt)"
    [ "$seen" -le "$pvs" ] || fail "cell $cell sees $seen objects, more than its PVS of $pvs"
  done < cells.csv
  rc=0
  "$validate" city.city.json one.pvs --viewpoints 0 --tightness-cells 2 \
    --cells-csv missing/dir/cells.csv > /dev/null 2> stderr.txt || rc=$?
  [ "$rc" = 5 ] || fail "unwritable --cells-csv: exit $rc, expected 5: $(cat stderr.txt)"
  grep -q 'missing/dir/cells.csv' stderr.txt || fail "the message lacks the path: $(cat stderr.txt)"
  absent missing
  # Without --quiet: the summary names cells, PVS sizes and stage times.
  "$preprocess" city.city.json --max-cell-edge 40 --epsilon 3 --region region.geojson \
    -o three.pvs 2> stderr.txt
  same one.pvs three.pvs
  for word in 'cells:' 'objects:' 'PVS:' 'culled' 'time:' 'visibility' 'peak'; do
    grep -q "$word" stderr.txt || fail "summary lacks '$word': $(cat stderr.txt)"
  done
  ;;

resume)
  make_reference
  # Kill points: once the first record is out, then spread over the run (with jitter).
  points=(record)
  for f in 20 45 70 90; do points+=($(( ref_ms * f / 100 + RANDOM % 50 ))); done
  resumed_from_records=0
  i=0
  for when in "${points[@]}"; do
    i=$((i + 1))
    threads=$(( i % 2 + 1 ))
    bake_and_kill k$i.pvs "$when" 2
    # A kill leaves no output or the whole output (it is renamed into place), never a part.
    if [ -e k$i.pvs ]; then
      same ref.pvs k$i.pvs
      echo "kill point $when ms: the output was complete already (killed=$killed)"
      rm k$i.pvs
    fi
    "$preprocess" "${bake[@]}" --threads "$threads" -o k$i.pvs --resume --report k$i.json
    same ref.pvs k$i.pvs
    absent k$i.pvs.journal
    no_temporaries
    from_journal=$(sed -n 's/.*"cells_from_journal": \([0-9]*\).*/\1/p' k$i.json)
    echo "kill point $when ms (threads on resume: $threads): $from_journal cells from the journal"
    [ "${from_journal:-0}" -gt 0 ] && resumed_from_records=$((resumed_from_records + 1))
  done
  [ "$resumed_from_records" -ge 1 ] || fail "no kill left a journal with records to resume"
  ;;

torn)
  make_reference
  # A torn last record and a garbage tail (as a power loss leaves) are cut off.
  for tail in torn garbage; do
    bake_and_kill $tail.pvs record 1
    [ "$killed" = 1 ] || fail "the bake finished before its first record could be killed"
    size=$(stat -c %s $tail.pvs.journal)
    if [ $tail = torn ] && [ "$size" -gt 44 ]; then
      truncate -s $((size - 3)) $tail.pvs.journal
    else
      head -c 100 /dev/urandom >> $tail.pvs.journal
    fi
    "$preprocess" "${bake[@]}" --threads 2 -o $tail.pvs --resume
    same ref.pvs $tail.pvs
  done
  # --resume without a journal simply bakes.
  "$preprocess" "${bake[@]}" -o fresh.pvs --resume
  same ref.pvs fresh.pvs
  ;;

mismatch)
  bake_and_kill other.pvs record 1
  [ "$killed" = 1 ] || fail "the bake finished before it could be killed"
  journal_size=$(stat -c %s other.pvs.journal)
  # Other settings (cell edge 35 m instead of 40 m): refused, and the journal is kept.
  rc=0
  "$preprocess" city.city.json --region region.geojson --epsilon 3 --max-cell-edge 35 \
    -o other.pvs --resume --quiet 2> stderr.txt || rc=$?
  [ "$rc" = 2 ] || fail "exit status $rc for a mismatched journal, expected 2"
  grep -q 'other.pvs.journal' stderr.txt || fail "message does not name the journal: $(cat stderr.txt)"
  grep -q 'other inputs or settings' stderr.txt || fail "message lacks the reason: $(cat stderr.txt)"
  absent other.pvs
  [ "$(stat -c %s other.pvs.journal)" = "$journal_size" ] || fail "the refused journal was changed"
  # Other inputs (another city): refused too.
  "$citygen" --size-km2 0.1 --seed 4 -q -o city4.city.json
  rc=0
  "$preprocess" city4.city.json --region region.geojson --epsilon 3 --max-cell-edge 40 \
    -o other.pvs --resume --quiet 2> stderr.txt || rc=$?
  [ "$rc" = 2 ] || fail "exit status $rc for a journal of other inputs, expected 2"
  # Not a journal at all.
  echo '{"not": "a journal"}' > junk.pvs.journal
  rc=0
  "$preprocess" "${bake[@]}" -o junk.pvs --resume 2> stderr.txt || rc=$?
  [ "$rc" = 2 ] || fail "exit status $rc for a file that is no journal, expected 2"
  grep -q 'not an urbanpvs-preprocess journal' stderr.txt || fail "$(cat stderr.txt)"
  # Without --resume the stale journal is replaced and the bake succeeds.
  "$preprocess" city.city.json --region region.geojson --epsilon 3 --max-cell-edge 35 \
    -o other.pvs --quiet
  absent other.pvs.journal
  [ -s other.pvs ] || fail "no output after replacing the journal"
  ;;

failures)
  expect() {  # expect RC WHAT -- command...: runs it, checks the exit status, prints stderr
    local want=$1 what=$2 rc=0
    shift 3
    "$@" 2> stderr.txt || rc=$?
    [ "$rc" = "$want" ] || fail "$what: exit status $rc, expected $want; stderr: $(cat stderr.txt)"
    echo "$what: exit $rc: $(head -n 1 stderr.txt)"
  }
  expect 5 "output directory missing" -- "$preprocess" "${bake[@]}" -o no/such/dir/out.pvs
  absent no
  # A directory nobody can write into, even root (CI runs as root, who ignores permission
  # bits): a path under a regular file.
  touch plainfile
  expect 5 "unwritable output directory" -- "$preprocess" "${bake[@]}" -o plainfile/out.pvs
  [ -f plainfile ] && [ ! -s plainfile ] || fail "plainfile was changed"
  if [ "$(id -u)" != 0 ]; then
    mkdir readonly && chmod 555 readonly
    expect 5 "read-only output directory" -- "$preprocess" "${bake[@]}" -o readonly/out.pvs
    [ -z "$(ls -A readonly)" ] || fail "files left in readonly/"
  else
    echo "note: running as root: the read-only directory case is covered by plainfile/ above"
  fi
  expect 5 "output is a directory" -- "$preprocess" "${bake[@]}" -o .
  expect 5 "report unwritable" -- "$preprocess" "${bake[@]}" -o r.pvs --report no/such/r.json
  absent r.pvs
  no_temporaries
  expect 11 "invalid JSON input" -- "$preprocess" "$bad/truncated.city.json" -o bad.pvs --quiet
  grep -q truncated.city.json stderr.txt || fail "the message does not name the input"
  absent bad.pvs bad.pvs.journal
  expect 15 "missing height with --strict" -- "$preprocess" "$bad/geojson_missing_height.geojson" \
    -o bad.pvs --strict
  grep -q 'relation/777' stderr.txt || fail "the message does not name the building"
  absent bad.pvs bad.pvs.journal
  expect 14 "bow-tie with --strict" -- "$preprocess" "$bad/geojson_bowtie.geojson" -o bad.pvs \
    --strict
  grep -q 'geojson_bowtie.geojson: way/1001: invalid geometry: ring intersects itself' \
    stderr.txt || fail "the message does not name the building and the problem"
  absent bad.pvs bad.pvs.journal
  expect 19 "malformed CityGML" -- "$preprocess" "$bad/citygml_mismatched_tag.gml" -o bad.pvs
  grep -q 'citygml_mismatched_tag.gml: line 5, column 6: invalid XML: mismatched tag' \
    stderr.txt || fail "the message does not name the line and the problem"
  absent bad.pvs bad.pvs.journal
  expect 13 "unknown reference system" -- "$preprocess" "$bad/cityjson_unknown_crs.city.json" -o bad.pvs
  grep -q 'cityjson_unknown_crs.city.json: unknown coordinate reference system: cannot interpret "https://example.org/crs/MyLocalGrid"' \
    stderr.txt || fail "the message does not name the file and the system"
  absent bad.pvs bad.pvs.journal
  expect 2 "missing input file" -- "$preprocess" no_such_city.json -o bad.pvs
  expect 2 "no output given" -- "$preprocess" city.city.json
  expect 2 "pixel too large" -- "$preprocess" city.city.json -o bad.pvs --epsilon 1 --pixel 2
  grep -qi 'pixel' stderr.txt || fail "the message does not name the pixel size"
  expect 2 "zero threads" -- "$preprocess" city.city.json -o bad.pvs --threads 0
  expect 2 "bad eye band" -- "$preprocess" city.city.json -o bad.pvs --eye-band 2
  expect 2 "bad backend" -- "$preprocess" city.city.json -o bad.pvs --backend vulkan
  echo '{"epsilon": 1, "max_cel_edge": 3}' > typo.json
  expect 2 "unknown config key" -- "$preprocess" city.city.json -o bad.pvs --config typo.json
  grep -q max_cel_edge stderr.txt || fail "the message does not name the unknown key"
  absent bad.pvs bad.pvs.journal
  ;;

config)
  "$preprocess" "${bake[@]}" --threads 1 -o cli.pvs
  # Paths in the config are relative to it; the command line's --epsilon wins over the config's.
  mkdir conf
  mv region.geojson conf/
  cat > conf/settings.json <<'JSON'
{"max-cell-edge": 40, "region": "region.geojson", "epsilon": 5, "threads": 2, "quiet": true,
 "eye_band": "0:2", "report": "config-report.json"}
JSON
  "$preprocess" city.city.json --config conf/settings.json --epsilon 3 -o config.pvs
  same cli.pvs config.pvs
  [ -s conf/config-report.json ] || fail "the report named in the config was not written"
  grep -q '"epsilon_m": 3,' conf/config-report.json || fail "epsilon of the command line not used"
  ;;

repairs)
  # Repair, don't refuse: a bow-tie building is repaired, one without height is kept as an object
  # that occludes nothing; both are in the file, the summary and the report.
  cat > broken.geojson <<'JSON'
{"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:3067"}},
 "features": [
  {"type": "Feature", "id": "bowtie", "properties": {"building": "yes", "height": 12},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [30, 0], [0, 20], [30, 20], [0, 0]]]}},
  {"type": "Feature", "id": "no-height", "properties": {"building": "yes"},
   "geometry": {"type": "Polygon", "coordinates": [[[60, 0], [70, 0], [70, 10], [60, 10], [60, 0]]]}},
  {"type": "Feature", "id": "house", "properties": {"building": "yes", "height": 9},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 60], [20, 60], [20, 75], [0, 75], [0, 60]]]}}
 ]}
JSON
  "$preprocess" broken.geojson -o broken.pvs --max-cell-edge 20 --epsilon 2 --report broken.json \
    2> stderr.txt || fail "the bake failed: $(cat stderr.txt)"
  grep -q 'input:       1 geometric repairs, 1 objects that occlude nothing' stderr.txt ||
    fail "the summary does not count the repair and the non-occluding object: $(cat stderr.txt)"
  grep -q 'repaired:    broken.geojson: bowtie: outer ring: ring has zero area (ring intersects itself' stderr.txt || fail "repair not listed"
  grep -q 'no occluder: broken.geojson: no-height: no height' stderr.txt ||
    fail "non-occluding object not listed"
  grep -q '"repairs": \[' broken.json || fail "report lacks repairs"
  grep -q 'no-height: no height' broken.json || fail "report lacks the non-occluding object"
  "$inspect" broken.pvs > summary.txt
  grep -q 'objects:     3' summary.txt || fail "an object is missing from the file: $(cat summary.txt)"
  "$validate" broken.geojson broken.pvs --viewpoints 300 --tightness-viewpoints 20 ||
    fail "urbanpvs-validate found misses (or failed)"
  ;;

terrain)
  # GeoJSON buildings on a DEM: the slope z = 20 + 0.2 x, 10 m pixels over -400..600 m, with no
  # reference system (taken as the city's, with a warning).
  write_tiles
  awk 'BEGIN { print "ncols 100\nnrows 100\nxllcorner -400\nyllcorner -400\ncellsize 10";
               print "NODATA_value -9999";
               for (r = 0; r < 100; r++) { line = "";
                 for (c = 0; c < 100; c++) line = line sprintf("%g ", 20 + 0.2 * (-400 + (c + 0.5) * 10));
                 print line } }' > slope.asc
  "$preprocess" tiles.geojson -o slope.pvs --max-cell-edge 20 --epsilon 2 --terrain slope.asc \
    --report slope.json 2> stderr.txt || fail "the bake with --terrain failed: $(cat stderr.txt)"
  grep -q '^terrain:     slope.asc (AAIGrid, (none), 100 x 100 pixels of 10.0 x 10.0 m), resampled every 5.0 m' \
    stderr.txt || fail "the summary does not describe the terrain: $(cat stderr.txt)"
  grep -q 'warning:     slope.asc: the raster names no reference system' stderr.txt ||
    fail "no warning for a raster without a reference system"
  grep -q '"terrain": "slope.asc (AAIGrid' slope.json || fail "the report lacks the terrain"
  # Every cell's eye band lies on the slope: its lowest point is the ground at the cell's
  # western corner, 20 + 0.2 x, so no cell reaches below the slope's lowest ground under the
  # default region (x >= -50: z >= 10) or starts at z = 0.
  "$inspect" slope.pvs --json > dump.json
  grep -o '"z":\[[^],]*' dump.json | sed 's/"z":\[//' > zmin.txt
  [ -s zmin.txt ] || fail "no cells in the dump"
  awk '$1 < 9.9 { bad = 1 } $1 > 30 { high = 1 } END { exit bad || !high }' zmin.txt ||
    fail "cells do not follow the terrain: lowest $(sort -g zmin.txt | head -1), highest $(sort -g zmin.txt | tail -1)"
  "$validate" tiles.geojson slope.pvs --terrain slope.asc --viewpoints 400 \
    --tightness-viewpoints 50 || fail "urbanpvs-validate found misses on the terrain"
  # The DEM as sloped squares (--terrain-planes): counted as the terrain's occluders, stored in
  # the file's settings, and still no miss.
  "$preprocess" tiles.geojson -o planes.pvs --max-cell-edge 20 --epsilon 2 --terrain slope.asc \
    --terrain-planes 20 2> stderr.txt || fail "--terrain-planes: $(cat stderr.txt)"
  grep -q '^objects: .*, [1-9][0-9]* of the terrain)' stderr.txt ||
    fail "the summary does not count the terrain's squares: $(cat stderr.txt)"
  "$inspect" planes.pvs | grep -q 'property:    terrain_planes_m = 20' ||
    fail "the setting is not in the file"
  "$validate" tiles.geojson planes.pvs --terrain slope.asc --viewpoints 400 \
    --tightness-viewpoints 50 || fail "urbanpvs-validate found misses with --terrain-planes"
  # A file GDAL cannot read as a raster: exit 17, the file named, nothing written.
  rc=0
  "$preprocess" tiles.geojson -o bad.pvs --terrain tiles.geojson --quiet 2> stderr.txt || rc=$?
  [ "$rc" -eq 17 ] || fail "a non-raster DEM gave exit $rc, not 17"
  grep -q 'tiles.geojson: unsupported format: not a raster GDAL can read' stderr.txt ||
    fail "wrong message: $(cat stderr.txt)"
  absent bad.pvs
  # --cells FILE is --region FILE: the same cells and PVSs, the region in the metadata.
  cat > square.geojson <<'JSON'
{"type": "Polygon", "coordinates": [[[-20, -20], [90, -20], [90, 90], [-20, 90], [-20, -20]]]}
JSON
  "$preprocess" tiles.geojson -o region.pvs --max-cell-edge 20 --epsilon 2 --region square.geojson --quiet
  "$preprocess" tiles.geojson -o cells.pvs --max-cell-edge 20 --epsilon 2 --cells square.geojson --quiet
  "$inspect" region.pvs --json | sed -n '/^"cells":\[/,$p' > region.cells
  "$inspect" cells.pvs --json | sed -n '/^"cells":\[/,$p' > cells.cells
  [ -s cells.cells ] || fail "no cells in the dump"
  same region.cells cells.cells
  "$inspect" cells.pvs | grep -q 'property:    region = square.geojson' ||
    fail "--cells FILE does not record its region"
  rc=0
  "$preprocess" tiles.geojson -o both.pvs --cells square.geojson --region square.geojson 2> stderr.txt || rc=$?
  [ "$rc" -eq 2 ] || fail "--cells FILE with --region gave exit $rc, not 2"
  grep -q 'urbanpvs-preprocess: --cells square.geojson and --region square.geojson both name a region: give one' \
    stderr.txt || fail "wrong message: $(cat stderr.txt)"
  rc=0
  "$preprocess" tiles.geojson -o none.pvs --cells nosuch.geojson 2> stderr.txt || rc=$?
  [ "$rc" -eq 2 ] || fail "--cells with a missing file gave exit $rc, not 2"
  grep -q -- '--cells must be everywhere, streets or an existing region file, got "nosuch.geojson"' \
    stderr.txt || fail "wrong message: $(cat stderr.txt)"
  ;;

payloads)
  # --payload NAME carries a property into the file: strings as given, numbers as JSON text,
  # nothing for a building without it; the file says where the values came from. Its version
  # is the lowest that holds it: 2.2 for the default coded PVS, 2.1 (payloads) or 2.0 (none)
  # with --pvs-coding varint.
  write_tiles
  "$preprocess" tiles.geojson -o tiles.pvs --max-cell-edge 20 --epsilon 2 --payload tile --quiet ||
    fail "the bake with --payload failed"
  "$inspect" tiles.pvs > summary.txt
  grep -q 'format:      2.2' summary.txt || fail "not a 2.2 file: $(cat summary.txt)"
  grep -q 'payloads:    2 of 3 objects, from "tile"' summary.txt ||
    fail "payloads not counted: $(cat summary.txt)"
  "$inspect" tiles.pvs --json > dump.json
  grep -q '"id":"a","payload":"t/0/1"' dump.json || fail "string payload lost"
  grep -q '"id":"b","payload":"42"' dump.json || fail "number payload not its JSON text"
  grep -q '"id":"c","payload":""' dump.json || fail "a building without the property has a payload"
  "$preprocess" tiles.geojson -o plain.pvs --max-cell-edge 20 --epsilon 2 --quiet
  "$inspect" plain.pvs | grep -q 'format:      2.2' || fail "a default bake is not 2.2"
  "$preprocess" tiles.geojson -o old.pvs --max-cell-edge 20 --epsilon 2 --quiet \
    --pvs-coding varint
  "$inspect" old.pvs | grep -q 'format:      2.0' || fail "a varint bake without --payload is not 2.0"
  "$preprocess" tiles.geojson -o old1.pvs --max-cell-edge 20 --epsilon 2 --quiet \
    --pvs-coding varint --payload tile
  "$inspect" old1.pvs | grep -q 'format:      2.1' || fail "a varint bake with --payload is not 2.1"
  "$inspect" old1.pvs --json > old1.json
  grep -q '"id":"a","payload":"t/0/1"' old1.json || fail "2.1 payload lost"
  sed 's/"minor":1/"minor":2/' old1.json | cmp - dump.json ||
    fail "the varint and exp-golomb files of one bake do not hold the same"
  "$preprocess" tiles.geojson -o none.pvs --max-cell-edge 20 --epsilon 2 --payload nosuch \
    --report none.json 2> stderr.txt || fail "the bake with an unknown --payload failed"
  grep -q '  warning:     --payload nosuch: no object has this attribute, property or tag' stderr.txt ||
    fail "no warning for a payload key no object has: $(cat stderr.txt)"
  grep -q '"warnings": \[' none.json || fail "report lacks the warnings"
  ;;

help)
  "$preprocess" --help > help.txt
  for option in --output --epsilon --pixel --max-cell-edge --eye-band --region --default-height \
                --threads --backend --method --report --resume --quiet --config --strict \
                --max-height --payload; do
    grep -q -- "$option" help.txt || fail "--help does not list $option"
  done
  ;;

citygml)
  # A CityGML 2.0 district (two buildings, a building part, xlinks, a compound reference
  # system) bakes with the defaults and the validator, reading the same file, finds no miss.
  gml="$bad/../citygml/two_buildings.gml"
  "$preprocess" "$gml" -o gml.pvs --quiet
  "$inspect" gml.pvs > summary.txt
  grep -q '^objects: *2$' summary.txt || fail "expected 2 objects: $(cat summary.txt)"
  grep -q 'EPSG:25832' summary.txt || fail "the reference system is not EPSG:25832"
  "$validate" "$gml" gml.pvs --viewpoints 200 --seed 5 > validate.txt \
    || fail "validation failed: $(cat validate.txt)"
  grep -q 'misses: 0' validate.txt || fail "misses: $(cat validate.txt)"
  no_temporaries
  ;;

gis)
  # A shapefile (ETRS89 / UTM 32N in Esri's WKT, no EPSG code in it; the height in a field of
  # its own, HOEHE; a shed without height) bakes with --height-field and the validator, reading
  # the same file with the same option, finds no miss. A layer it does not have exits 12.
  shp="$bad/../gis/district.shp"
  "$preprocess" "$shp" -o shp.pvs --height-field HOEHE --quiet || fail "the shapefile did not bake"
  "$inspect" shp.pvs > summary.txt
  grep -q '^objects: *6$' summary.txt || fail "expected 6 objects: $(cat summary.txt)"
  grep -q 'EPSG:25832' summary.txt || fail "the reference system is not EPSG:25832"
  "$validate" "$shp" shp.pvs --height-field HOEHE --viewpoints 200 --seed 5 > validate.txt \
    || fail "validation failed: $(cat validate.txt)"
  grep -q 'misses: 0' validate.txt || fail "misses: $(cat validate.txt)"
  set +e
  "$preprocess" "$shp" -o layer.pvs --layer roofs --quiet 2> layer.err
  code=$?
  set -e
  [ "$code" = 12 ] || fail "--layer roofs: exit $code, expected 12"
  grep -qF "district.shp: unexpected structure: no layer \"roofs\" (layers: district)" layer.err \
    || fail "--layer roofs: $(cat layer.err)"
  absent layer.pvs
  no_temporaries
  ;;

solids)
  # Buildings that are not height fields (an arcade, an overhang under a gabled roof) are
  # shrunk in 3D with --solid-step (TetGen), the gabled house and the sheds are left to the
  # blocks, and the validator, which reads the input's own faces, finds no miss. A build without TetGen says
  # so and exits 2, leaving nothing behind.
  solids="$bad/../solids/solids.city.json"
  set +e
  "$preprocess" "$solids" -o solids.pvs --solid-step 1 --report report.json > bake.txt 2> bake.err
  code=$?
  set -e
  if grep -q 'URBANPVS_TETGEN=OFF' bake.err; then
    [ "$code" = 2 ] || fail "without TetGen: exit $code, expected 2"
    grep -qF -- "--solid-step needs TetGen: this build was configured with URBANPVS_TETGEN=OFF" \
      bake.err || fail "without TetGen: $(cat bake.err)"
    absent solids.pvs
  else
    [ "$code" = 0 ] || fail "--solid-step 1: exit $code: $(cat bake.err)"
    grep -q '^solids: *2 buildings that are not height fields shrunk in 3D into [0-9]* occluders, 0 gave none' \
      bake.err || fail "expected 2 solids shrunk: $(grep -E '^(objects|solids)' bake.err)"
    grep -q '"solids_shrunk": *2' report.json || fail "the report has no solids_shrunk of 2"
    "$validate" "$solids" solids.pvs --viewpoints 200 --seed 5 > validate.txt \
      || fail "validation failed: $(cat validate.txt)"
    grep -q 'misses: 0' validate.txt || fail "misses: $(cat validate.txt)"
    # Through the passage, from in front of the arcade, the shed behind it is seen: an occluder
    # over the passage would hide it.
    echo "85015 446020 1.5" | "$inspect" solids.pvs --query - > query.txt
    grep -q 'shed_behind_arcade' query.txt || fail "the shed is hidden through the passage: $(cat query.txt)"
    # Without ground faces the blocks give the arcade and the overhang nothing (raised parts);
    # the 3D route closes them on the ground, and the PVSs shrink without a miss.
    open="$bad/../solids/solids_no_ground.city.json"
    "$preprocess" "$open" -o open2d.pvs --quiet || fail "the city without ground faces did not bake"
    "$preprocess" "$open" -o open3d.pvs --solid-step 1 --quiet 2> open3d.err \
      || fail "--solid-step 1 without ground faces: $(cat open3d.err)"
    mean2d=$("$inspect" open2d.pvs | sed -n 's/^pvs size: .*mean \([0-9.]*\),.*/\1/p')
    mean3d=$("$inspect" open3d.pvs | sed -n 's/^pvs size: .*mean \([0-9.]*\),.*/\1/p')
    awk -v a="$mean3d" -v b="$mean2d" 'BEGIN { exit !(a < b) }' \
      || fail "mean PVS with the 3D route $mean3d, without $mean2d"
    "$validate" "$open" open3d.pvs --viewpoints 200 --seed 5 > validate_open.txt \
      || fail "validation failed: $(cat validate_open.txt)"
    grep -q 'misses: 0' validate_open.txt || fail "misses: $(cat validate_open.txt)"
  fi
  no_temporaries
  ;;

sloped)
  # Sloped roofs, the default on LoD2 input: the roof faces become occluders with sloped tops
  # (the summary and the report count them, the file's metadata names the setting), the PVSs
  # shrink against the same city with prisms cut at the eaves (--no-sloped-roofs, or false in
  # a --config file), and the validator finds no miss. The flag and its negation together are
  # a usage error. Cells of up to 36 m (712 rather than 2,003 at the default 18 m) keep the
  # three bakes short under the sanitizers; the roofs and their setting are what is tested.
  "$citygen" --size-km2 0.1 --seed 8 --roofs lod2 -q -o lod2.city.json
  "$preprocess" lod2.city.json -o eaves.pvs --max-cell-edge 36 --no-sloped-roofs --quiet \
    || fail "the LoD2 city did not bake with --no-sloped-roofs"
  "$preprocess" lod2.city.json -o sloped.pvs --max-cell-edge 36 --report report.json \
    > bake.txt 2> bake.err || fail "the default bake: $(cat bake.err)"
  grep -q '^objects: .*, [1-9][0-9]* under sloped roof faces)' bake.err \
    || fail "no roof face occluders: $(grep '^objects' bake.err)"
  grep -q '"roof_plane_occluders": *[1-9]' report.json || fail "the report counts no roof faces"
  printf '{"sloped_roofs": false, "max-cell-edge": 36}\n' > eaves.json
  "$preprocess" lod2.city.json -o config.pvs --config eaves.json --quiet \
    || fail "sloped_roofs: false in a config failed"
  cmp -s config.pvs eaves.pvs || fail "sloped_roofs: false in a config is not --no-sloped-roofs"
  rc=0
  "$preprocess" lod2.city.json -o both.pvs --sloped-roofs --no-sloped-roofs 2> both.err || rc=$?
  [ "$rc" -eq 2 ] || fail "--sloped-roofs with --no-sloped-roofs: exit $rc, expected 2"
  grep -q 'excludes' both.err || fail "no reason for refusing both: $(cat both.err)"
  [ ! -e both.pvs ] || fail "both.pvs written on a usage error"
  "$inspect" eaves.pvs | grep -q 'property:    sloped_roofs = false' \
    || fail "--no-sloped-roofs is not in the file"
  "$inspect" sloped.pvs > summary.txt
  grep -q 'property:    sloped_roofs = true' summary.txt || fail "the setting is not in the file"
  mean_eaves=$("$inspect" eaves.pvs | sed -n 's/^pvs size: .*mean \([0-9.]*\),.*/\1/p')
  mean_sloped=$(sed -n 's/^pvs size: .*mean \([0-9.]*\),.*/\1/p' summary.txt)
  awk -v a="$mean_sloped" -v b="$mean_eaves" 'BEGIN { exit !(a < b) }' \
    || fail "mean PVS with sloped roofs $mean_sloped, without $mean_eaves"
  "$validate" lod2.city.json sloped.pvs --viewpoints 200 --seed 5 > validate.txt \
    || fail "validation failed: $(cat validate.txt)"
  grep -q 'misses: 0' validate.txt || fail "misses: $(cat validate.txt)"
  no_temporaries
  ;;

*)
  fail "unknown case $case_name"
  ;;
esac
echo "PASS: $case_name"
