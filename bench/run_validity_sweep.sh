#!/usr/bin/env bash
# The validity sweep: every cloud x seeds 1-20 x 1,000 / 3,000 / 10,000 / 30,000 vertices (the
# sizes each cloud can carry), with and without the finishing stage. Writes
# bench/results/validity.csv (one row per run) and bench/results/validity.md (the summary).
#   bench/run_validity_sweep.sh          the full sweep, on the clouds in ../shared/data, or on
#                                        the bundled bunny when they are not there
#   bench/run_validity_sweep.sh --ci     the reduced sweep CI runs (a few clouds, seeds and sizes,
#                                        about two minutes); fails on any crossing pair or inward
#                                        face of the finished meshes
# The single-view scan (bunny_scan090) is exempt from the check: a closed surface cannot represent
# an open sheet; it must only end, in bounded time, with the warning.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target validity_sweep > /dev/null
data=../shared/data
mkdir -p bench/results
if [ "${1:-}" = "--ci" ]; then
  out=build/validity-ci
  mkdir -p "$out"
  clouds=(examples/data/bunny.ply)
  for c in horse rocker_arm; do [ -f "$data/$c.ply" ] && clouds+=("$data/$c.ply"); done
  ./build/bench/validity_sweep "${clouds[@]}" --seeds 1-3 --sizes 1000,3000 --finish on \
    --csv "$out/validity.csv" --md "$out/validity.md" --check 2> "$out/log.txt" || {
    cat "$out/validity.md"
    exit 1
  }
  cat "$out/validity.md"
  exit 0
fi
clouds=()
for c in bunny horse rocker_arm knot eight bunny_scan090; do [ -f "$data/$c.ply" ] && clouds+=("$data/$c.ply"); done
[ ${#clouds[@]} -eq 0 ] && clouds=(examples/data/bunny.ply)
# Two processes side by side (one per core): the clouds split between them.
half=$(( (${#clouds[@]} + 1) / 2 ))
./build/bench/validity_sweep "${clouds[@]:0:$half}" --csv build/validity-a.csv --md build/validity-a.md \
  --exempt bunny_scan090 2> build/validity-a.log &
pid=$!
if [ ${#clouds[@]} -gt "$half" ]; then
  ./build/bench/validity_sweep "${clouds[@]:$half}" --csv build/validity-b.csv --md build/validity-b.md \
    --exempt bunny_scan090 2> build/validity-b.log
fi
wait $pid
cp build/validity-a.csv bench/results/validity.csv
[ -f build/validity-b.csv ] && tail -n +2 build/validity-b.csv >> bench/results/validity.csv
{
  echo "# Validity sweep"
  echo
  echo "Command: \`bench/run_validity_sweep.sh\` (Release). $(date -u +%Y-%m-%d). Per run: bench/results/validity.csv."
  echo
  sed -n '/^| cloud/,$p' build/validity-a.md | grep -v "runs in"
  [ -f build/validity-b.md ] && sed -n '/^| cloud/,$p' build/validity-b.md | tail -n +3 | grep -v "runs in"
  echo
  grep -h "runs in" build/validity-a.md build/validity-b.md 2> /dev/null || true
} > bench/results/validity.md
cat bench/results/validity.md
