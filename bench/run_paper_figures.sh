#!/usr/bin/env bash
# Renders the README's pictures into docs/ (needs bench/results/paper/table1.csv from
# bench/run_paper_experiments.sh for the heat map).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target paper_figures
mkdir -p docs
./build/bench/paper_figures examples/data/bunny.ply bench/results/paper/table1.csv docs
