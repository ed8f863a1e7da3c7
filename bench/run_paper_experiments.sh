#!/usr/bin/env bash
# Re-runs the paper's experiments (Table 1 grid, section 6.1, Table 3) on the bundled bunny and
# writes bench/results/paper/{table1.csv,table1_runs.csv,table3.csv,paper_experiments.md}.
#   bench/run_paper_experiments.sh [--seeds S] [--vertices N] [--quick]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target paper_experiments
mkdir -p bench/results/paper
./build/bench/paper_experiments examples/data/bunny.ply bench/results/paper "$@"
rm -f bench/results/paper/bunny_30000.ply   # large; regenerate rather than commit
