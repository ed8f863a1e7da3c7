#!/usr/bin/env bash
# The single-view scan (../shared/data/bunny_scan090.ply, one range image of the bunny) in
# topology open at 30,000 vertices, seeds 1-12, against the scan's own triangulation
# (bunny_scan090_mesh.ply), and timed against the closed bundled bunny at the same size in the
# same run. Writes bench/results/single-view.{md,csv}. Needs ../shared/data.
set -euo pipefail
cd "$(dirname "$0")/.."
data=../shared/data
for f in bunny_scan090.ply bunny_scan090_mesh.ply; do
  [ -f "$data/$f" ] || { echo "run_single_view.sh: $data/$f not found"; exit 2; }
done
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target single_view > /dev/null
mkdir -p bench/results
./build/bench/single_view "$data/bunny_scan090.ply" "$data/bunny_scan090_mesh.ply" examples/data/bunny.ply \
  --vertices "${VERTICES:-30000}" --seeds "${SEEDS:-1-12}" \
  --md bench/results/single-view.md --csv bench/results/single-view.csv
