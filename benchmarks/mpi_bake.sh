#!/usr/bin/env bash
# The distributed bake (issue 16) on this machine, never run by ctest:
#   1. the generated 4 km² city (seed 7, flat) baked by 1 rank x 2 threads and by 2 ranks x 1
#      thread (mpirun): cells, read + scene seconds (each rank builds the scene itself),
#      visibility seconds, cells/s, peak MiB per rank, and whether the two files are identical;
#   2. the memory one rank needs on a generated city of SIZE km² (default 16): the process is
#      stopped once it has computed cells, after its scene and cull maps are built, and its
#      peak resident memory (VmHWM) is the replicated scene's cost per rank.
#      It gives up after LIMIT seconds (default 1200) and prints the peak so far.
#   benchmarks/mpi_bake.sh [BUILD_DIR] [SIZE_KM2] [LIMIT_S] [all|memory]
# "memory" runs only part 2 (about a minute at 16 km²; part 1 takes about 25 minutes).
set -euo pipefail
build=$(cd "${1:-build/release}" && pwd)
big=${2:-16}
limit=${3:-1200}
parts=${4:-all}
bake=$build/preprocess/urbanpvs-preprocess
citygen=$build/cities/urbanpvs-citygen
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

field() { sed -n "s|^$1 *\\(.*\\)|\\1|p" "$2" | head -n 1; }
row() {  # label, summary file
  local cells time ranks
  cells=$(field cells: "$2")
  time=$(field time: "$2")
  ranks=$(field ranks: "$2")
  printf '| %s | %s | %s | %s | %s |\n' "$1" "${cells%% (*}" \
    "$(sed -n 's|.* at \([0-9.]*\) cells/s.*|\1|p' "$2")" "$time" \
    "${ranks:-1 ($(field memory: "$2"))}"
}

if [ "$parts" = all ]; then
  "$citygen" --size-km2 4 --seed 7 --roofs flat -q -o city4.city.json
  "$bake" city4.city.json -o one.pvs --threads 2 2> one.txt
  mpirun --oversubscribe --allow-run-as-root -n 2 "$bake" city4.city.json -o two.pvs --threads 1 \
    2> two.txt
  echo
  echo "| bake of the generated 4 km² city | cells | cells/s | time | ranks (cells; balance; peak per rank) |"
  echo "|---|---|---|---|---|"
  row "1 rank x 2 threads" one.txt
  row "2 ranks x 1 thread" two.txt
  if cmp -s one.pvs two.pvs; then echo "files: identical"; else echo "files: DIFFER"; fi
fi

"$citygen" --size-km2 "$big" --seed 7 --roofs flat -q -o big.city.json
"$bake" big.city.json -o big.pvs --threads 1 2> big.txt &
pid=$!
start=$(date +%s)
while kill -0 "$pid" 2>/dev/null; do
  size=$(stat -c %s big.pvs.journal 2>/dev/null || echo 0)
  if [ "$size" -gt 4096 ]; then break; fi
  if [ $(( $(date +%s) - start )) -gt "$limit" ]; then
    echo "gave up after $limit s, before the first cells (still building the scene)"
    break
  fi
  sleep 0.5
done
hwm=$(sed -n 's/^VmHWM:[[:space:]]*\([0-9]*\) kB/\1/p' "/proc/$pid/status")
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
echo
echo "generated ${big} km² city: $(grep -m1 'scene:' big.txt | sed 's/^urbanpvs-preprocess: //')"
echo "$(grep -m1 'read ' big.txt | sed 's/^urbanpvs-preprocess: //')"
echo "peak memory of one rank once it computes cells: $((hwm / 1024)) MiB ($(( $(date +%s) - start )) s to get there)"
