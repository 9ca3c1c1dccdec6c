#!/usr/bin/env bash
# urbanpvs-preprocess under mpirun (issue 16), on a small generated city (0.1 km², seed 3):
#   1. mpirun -n 3 (1 thread per rank) gives the same bytes as one process with 2 threads; the
#      report lists 3 ranks whose cells add up to all cells;
#   2. a rank killed with SIGKILL partway fails the job: non-zero exit, no output file, no
#      temporary file, a journal with the finished cells;
#   3. mpirun -n 2 --resume continues that journal to the identical file, and leaves no journal.
# Usage: mpi_bake_test.sh WORK_DIR PREPROCESS CITYGEN MPIEXEC
set -euo pipefail
work=$1 preprocess=$2 citygen=$3 mpiexec=$4

rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
same() { cmp -s "$1" "$2" || fail "$1 and $2 differ"; }
# CI runs as root; more ranks than cores is fine for a test.
mpi=("$mpiexec" --oversubscribe --allow-run-as-root)

"$citygen" --size-km2 0.1 --seed 3 -q -o city.city.json
bake=(city.city.json --max-cell-edge 30 --epsilon 2)
"$preprocess" "${bake[@]}" --quiet --threads 2 -o ref.pvs
[ -s ref.pvs ] || fail "no reference file"

# 1. Three ranks, one thread each: the same bytes.
"${mpi[@]}" -n 3 "$preprocess" "${bake[@]}" --threads 1 -o three.pvs --report three.json \
  2> three.txt
same ref.pvs three.pvs
[ ! -e three.pvs.journal ] || fail "the journal of a finished job was left behind"
grep -q '^ranks: *3 (cells [0-9]*/[0-9]*/[0-9]*; most over mean' three.txt ||
  fail "the summary does not list the 3 ranks: $(cat three.txt)"
shares=$(sed -n 's|^ranks: *3 (cells \([0-9/]*\);.*|\1|p' three.txt)
total=$(sed -n 's|^cells: .*(\([0-9]*\) computed.*|\1|p' three.txt)
sum=0
IFS=/ read -ra parts <<< "$shares"
for n in "${parts[@]}"; do sum=$((sum + n)); done
[ "$sum" -eq "$total" ] || fail "the ranks' cells ($shares) do not add up to $total"
[ "$(grep -c '"rank":' three.json)" -eq 3 ] || fail "the report does not list 3 ranks"
grep -q '"load_balance":' three.json || fail "the report has no load balance"
echo "3 ranks computed $shares of $total cells"

# 2. Kill rank 1 once the journal holds finished cells (more than its 40-byte header).
"${mpi[@]}" -n 3 "$preprocess" "${bake[@]}" --quiet --threads 1 -o killed.pvs &
job=$!
victim=""
for _ in $(seq 1 3000); do
  if [ -z "$victim" ]; then
    for pid in $(pgrep -f "killed.pvs" || true); do
      if tr '\0' '\n' < "/proc/$pid/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
        victim=$pid
      fi
    done
  fi
  size=$(stat -c %s killed.pvs.journal 2>/dev/null || echo 0)
  if [ -n "$victim" ] && [ "$size" -gt 200 ]; then break; fi
  sleep 0.01
done
[ -n "$victim" ] || fail "rank 1 never started"
kill -9 "$victim" 2>/dev/null || fail "rank 1 ended before it could be killed (make the bake longer)"
rc=0
wait "$job" || rc=$?
[ "$rc" -ne 0 ] || fail "the job succeeded although rank 1 was killed"
[ ! -e killed.pvs ] || fail "a failed job left an output file"
left=$(ls -A | grep -E '\.tmp-[0-9]+$|\.journal\.new$' || true)
[ -z "$left" ] || fail "temporary files left: $left"
[ -s killed.pvs.journal ] || fail "no journal after the failed job"
echo "job failed with exit $rc after rank 1 was killed; journal $(stat -c %s killed.pvs.journal) bytes"

# 3. Resume with another number of ranks: the identical file.
"${mpi[@]}" -n 2 "$preprocess" "${bake[@]}" --threads 1 -o killed.pvs --resume \
  2> resumed.txt
same ref.pvs killed.pvs
[ ! -e killed.pvs.journal ] || fail "the journal of a finished job was left behind"
from_journal=$(sed -n 's|^cells: .* \([0-9]*\) from the journal.*|\1|p' resumed.txt)
[ "${from_journal:-0}" -gt 0 ] || fail "nothing was taken from the journal: $(cat resumed.txt)"
grep -q '^ranks: *2 ' resumed.txt || fail "the resumed job does not list 2 ranks"
echo "resumed with 2 ranks: $from_journal cells from the journal"
echo "OK"
