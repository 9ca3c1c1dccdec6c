#!/usr/bin/env bash
# OSM roof:shape as roof faces (geometry/city/RoofShapes.cpp), measured: writes an OSM-style
# GeoJSON district (6 x 6 blocks of 60 m, 16 m streets, two rows of rectangular houses per
# block, height = the roof's top as OSM has it, gabled / hipped / pyramidal / flat roofs with
# roof:height, half the gables with roof:orientation=across; seeded, so the same every run),
# bakes it with --sloped-roofs (the default) and --no-sloped-roofs, validates both, and prints
# one table row each: cells, occluders, roof-face occluders, mean PVS, visibility seconds,
# cells/s, misses and tightness. Run by hand (about a minute), never by ctest:
#   benchmarks/roof_shapes.sh [BUILD_DIR] [VIEWPOINTS] [THREADS]
set -euo pipefail
build=${1:-build/release}
viewpoints=${2:-300}
threads=${3:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bake=$build/preprocess/urbanpvs-preprocess
validate=$build/preprocess/validate/urbanpvs-validate

python3 - > "$work/roofs.geojson" <<'EOF'
import json, random
random.seed(5)
features, n = [], 0
block, street = 60.0, 16.0
for bi in range(6):
    for bj in range(6):
        x0, y0 = bi * (block + street), bj * (block + street)
        for row in range(2):
            x, yb = x0, y0 + row * block / 2
            while x < x0 + block - 6:
                w = min(random.uniform(7, 12), x0 + block - x)
                d = block / 2 - random.uniform(0, 4)
                ys = yb if row == 0 else yb + (block / 2 - d)
                eaves = random.choice([6, 9, 12, 15])
                roof = random.uniform(3, 6)
                shape = random.choices(["gabled", "hipped", "pyramidal", "flat"], [5, 3, 1, 1])[0]
                props = {"building": "house", "height": round(eaves + (roof if shape != "flat" else 0), 2)}
                if shape != "flat":
                    props["roof:shape"] = shape
                    props["roof:height"] = round(roof, 2)
                    if shape == "gabled" and random.random() < 0.5:
                        props["roof:orientation"] = "across"
                ring = [[x, ys], [x + w, ys], [x + w, ys + d], [x, ys + d], [x, ys]]
                coords = [[round(a + 100000, 3), round(b + 400000, 3)] for a, b in ring]
                features.append({"type": "Feature", "id": f"h{n}", "properties": props,
                                 "geometry": {"type": "Polygon", "coordinates": [coords]}})
                n += 1
                x += w + random.choice([0, 0, 0, 2.5])
crs = {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::28992"}}
print(json.dumps({"type": "FeatureCollection", "crs": crs, "features": features}))
EOF

echo "| roofs | cells | occluders | of them roof faces | mean PVS | visibility s | cells/s | misses | tightness |"
echo "|---|---|---|---|---|---|---|---|---|"
for mode in --sloped-roofs --no-sloped-roofs; do
  "$bake" "$work/roofs.geojson" -o "$work/city.pvs" --threads "$threads" "$mode" \
    --report "$work/report.json" --quiet
  read -r cells occ faces mean vis cps < <(python3 -c "
import json; r = json.load(open('$work/report.json')); c = r['counts']
print(c['cells'], c['occluders'], c['roof_plane_occluders'], '%.2f' % c['pvs_mean'],
      '%.2f' % r['seconds']['visibility'], '%.1f' % r['cells_per_second'])")
  set +e
  "$validate" "$work/roofs.geojson" "$work/city.pvs" --viewpoints "$viewpoints" > "$work/v.txt" 2>&1
  set -e
  misses=$(sed -n 's/.*misses: *\([0-9]*\).*/\1/p' "$work/v.txt" | head -n 1)
  tight=$(sed -n 's/^tightness: *\([0-9.]*\).*/\1/p' "$work/v.txt" | head -n 1)
  echo "| $mode | $cells | $occ | $faces | $mean | $vis | $cps | $misses | $tight |"
done
