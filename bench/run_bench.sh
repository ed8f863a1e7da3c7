#!/usr/bin/env bash
# Benchmarks the learning loop on the bundled bunny (Release build): 30,000 vertices with the
# edge swap on and off, and in topology sphere mode (the paper's algorithm, without the handle
# search of the default closed mode), RUNS runs each (default 5), median / min / max wall time excluding file
# I/O, iterations per second and the share of time per phase. Writes bench/results/bunny.csv
# and bench/results/summary.md (with the machine's description).
#   bench/run_bench.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target bench_reconstruct > /dev/null
mkdir -p bench/results
csv=bench/results/bunny.csv
echo "points,vertices,edge_swap,topology,runs,median_s,min_s,max_s,median_iterations_per_s,winner_pct,update_pct,split_pct,collapse_pct,swap_pct,median_finish_s" > "$csv"
out=$(mktemp)
for variant in "" "--no-edge-swap" "--topology sphere"; do
  # shellcheck disable=SC2086
  ./build/bench/bench_reconstruct examples/data/bunny.ply --vertices 30000 --runs "$runs" $variant --csv "$csv" |
    tee -a "$out"
done
{
  echo "# Benchmark: the bunny to 30,000 vertices"
  echo
  echo "Command: \`bench/run_bench.sh $runs\` (Release, one thread). $(date -u +%Y-%m-%d)."
  echo
  echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB."
  echo "Load average when the benchmark started: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo
  echo '```'
  cat "$out"
  echo '```'
} > bench/results/summary.md
rm -f "$out"
cat bench/results/summary.md
