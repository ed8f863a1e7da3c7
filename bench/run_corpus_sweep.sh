#!/usr/bin/env bash
# The corpus sweep: every cloud of ../shared/data and ../shared/data/corpus against its reference
# mesh (bench/corpus_sweep.cpp). The closed clouds (the bunny with its scanner holes among them) in
# topology closed at points / 2 and points / 6 vertices; the single range images in topology open
# at 20,000 and 30,000 vertices; the surface with many holes in topology open at 5,000 and 10,000.
# Seeds 1-10. Writes bench/results/corpus.{csv,md}.
#   bench/run_corpus_sweep.sh            the full sweep (about an hour on 2 cores)
#   bench/run_corpus_sweep.sh --ci       the reduced sweep CI runs: seed 1, the closed clouds at
#                                        points / 6, the range images open at 20,000 vertices; fails
#                                        on an error or crossing pairs, or, closed, on inward faces
#                                        or a genus above the reference's (a handle missed is
#                                        reported in the table, not failed: docs/algorithm.md)
#   bench/run_corpus_sweep.sh --seeds A-B [--out NAME]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target corpus_sweep > /dev/null
data=../shared/data
if [ ! -d "$data/corpus" ]; then echo "the corpus sweep needs ../shared/data/corpus"; exit 1; fi
seeds=1-10
name=corpus
ci=0
while [ $# -gt 0 ]; do
  case "$1" in
    --ci) ci=1; seeds=1; name=corpus-ci ;;
    --seeds) seeds=$2; shift ;;
    --out) name=$2; shift ;;
    *) echo "unknown option $1"; exit 2 ;;
  esac
  shift
done
closed=()
for c in bunny horse rocker_arm knot eight; do closed+=("$data/$c.ply"); done
for c in knot1 rotor_small femur joint helmet anchor bull camel diplodocus fandisk hand triceratops; do
  closed+=("$data/corpus/$c.ply")
done
scans=("$data/bunny_scan090.ply" "$data/corpus/scan_bun045.ply" "$data/corpus/scan_top2.ply" "$data/corpus/scan_ear_back.ply")
out=build/$name
mkdir -p "$out" bench/results
# The horse and the rocker arm have no reference mesh beside them: their genus from data/README.md.
sweep="./build/bench/corpus_sweep --genus horse=0,rocker_arm=1"
if [ $ci = 1 ]; then
  half=$(( ${#closed[@]} / 2 ))
  status=0
  $sweep "${closed[@]:0:$half}" --seeds 1 --fractions 6 --csv "$out/a.csv" --md "$out/a.md" --check 2> "$out/a.log" &
  pid=$!
  {
    $sweep "${closed[@]:$half}" --seeds 1 --fractions 6 --csv "$out/b.csv" --md "$out/b.md" --check 2> "$out/b.log" &&
      $sweep "${scans[@]}" --topology open --seeds 1 --sizes 20000 --csv "$out/d.csv" --md "$out/d.md" --check \
        2> "$out/d.log"
  } || status=1
  wait $pid || status=1
  cat "$out/a.md"; tail -n +3 "$out/b.md"; tail -n +3 "$out/d.md"
  # The check must see a defect where there is one: a closed mesh round a single view crosses
  # itself (scan_top2: a view in one part; bunny_scan090's two parts, each closed on its own,
  # come out valid at this size).
  if $sweep "$data/corpus/scan_top2.ply" --seeds 1 --sizes 3000 --csv "$out/control.csv" --md "$out/control.md" --check \
      2> /dev/null; then
    echo "FAILED: the check passed a closed mesh round a single view, which crosses itself"
    status=1
  else
    echo "The check fails on a closed mesh round a single view, as it must."
  fi
  [ $status = 0 ] || echo "FAILED: a run has an error or crossing pairs, or, closed, inward faces or a genus above the reference's"
  exit $status
fi
# Two processes side by side (one per core), the clouds split between them.
half=$(( ${#closed[@]} / 2 ))
$sweep "${closed[@]:0:$half}" --seeds "$seeds" --fractions 2,6 --csv "$out/a.csv" --md "$out/a.md" 2> "$out/a.log" &
pid=$!
{
  $sweep "${closed[@]:$half}" --seeds "$seeds" --fractions 2,6 --csv "$out/b.csv" --md "$out/b.md" 2> "$out/b.log"
  $sweep "$data/corpus/bull_with_holes.ply" --topology open --seeds "$seeds" --sizes 5000,10000 \
    --csv "$out/c.csv" --md "$out/c.md" 2> "$out/c.log"
} &
pid2=$!
wait $pid
$sweep "${scans[@]}" --topology open --seeds "$seeds" --sizes 20000,30000 --csv "$out/d.csv" --md "$out/d.md" \
  2> "$out/d.log"
wait $pid2
{
  cat "$out/a.csv"; for p in b c d; do tail -n +2 "$out/$p.csv"; done
} > "bench/results/$name.csv"
{
  echo "# Corpus sweep"
  echo
  echo "Command: \`bench/run_corpus_sweep.sh\` (Release), seeds $seeds. $(date -u +%Y-%m-%d). Per run: bench/results/$name.csv."
  echo "H: the Hausdorff distance between the mesh and the cloud over the reference mesh's own (the floor);"
  echo "to / from ref: distances from the mesh to the reference surface and back, in % of the diagonal."
  echo
  sed -n '/^| cloud/,/^$/p' "$out/a.md" | grep '^|'
  for p in b c d; do sed -n '/^| cloud/,/^$/p' "$out/$p.md" | grep '^|' | tail -n +3; done
  echo
  for p in a b c d; do tail -n 1 "$out/$p.md"; done
} > "bench/results/$name.md"
cat "bench/results/$name.md"
