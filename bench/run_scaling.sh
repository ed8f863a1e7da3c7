#!/usr/bin/env bash
# Scaling benchmarks (Release build, one thread), each configuration in its own process:
#   - output size: 1k, 10k, 30k, 100k, 300k and 1,000,000 vertices from the bunny upsampled to
#     3,594,700 points, and 1k, 10k, 30k from the bunny itself (35,947 points): time, iterations
#     per second, peak memory per vertex;
#   - input size: 30,000 vertices from the bunny at 35,947, 359,470, 3,594,700 and 35,947,000
#     points (upsampled 1, 10, 100 and 1000 times), and the smallest and largest of these timed
#     in alternation for the target's ratio;
#   - loading: read_points on the 3,594,700-point cloud as binary PLY and as XYZ text (warm page
#     cache).
# How the clouds are made and what is measured: bench/bench_scaling.cpp. Writes
# bench/results/scaling_output.csv, scaling_input.csv, scaling_pair.csv, loading.csv and
# scaling.md (with the machine's description and a line per performance target).
#   bench/run_scaling.sh [--quick] [RUNS] [RUNS_LARGEST]
# RUNS (default 5) runs per figure; RUNS_LARGEST (default RUNS) for the 1,000,000-vertex row only.
# --quick: small sizes only (up to 30,000 vertices and 3.6M points), to check the pipeline.
# NMESH_BUILD_DIR (default build) and NMESH_BUILD_JOBS (default 2) choose where and how the
# benchmark is built.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
if [[ "${1:-}" == "--quick" ]]; then quick=1; shift; fi
runs=${1:-5}
runs_largest=${2:-$runs}
build=${NMESH_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" -j "${NMESH_BUILD_JOBS:-2}" --target bench_scaling > /dev/null
bin="$build/bench/bench_scaling"
cloud=examples/data/bunny.ply
base=35947
dense=$((base * 100))
if (( quick )); then
  dense_sizes="1000 10000 30000"
  input_points="$base $((base * 10)) $((base * 100))"
else
  dense_sizes="1000 10000 30000 100000 300000 1000000"
  input_points="$base $((base * 10)) $((base * 100)) $((base * 1000))"
fi

mkdir -p bench/results
out_csv=bench/results/scaling_output.csv
in_csv=bench/results/scaling_input.csv
load_csv=bench/results/loading.csv
pair_csv=bench/results/scaling_pair.csv
md=bench/results/scaling.md
header="mode,cloud_points,upsample,vertices,runs,iterations,median_s,min_s,max_s,median_it_per_s,min_it_per_s,max_it_per_s,setup_median_s,loop_median_s,call_median_s,rss_before_mb,setup_peak_bytes_per_point,input_bytes_per_point,index_bytes_per_point,mesh_peak_mb,bytes_per_vertex,output_mesh_bytes_per_vertex,peak_minus_before_per_vertex"
echo "$header" > "$out_csv"
echo "$header" > "$in_csv"
echo "format,points,file_mb,runs,median_s,min_s,max_s,median_mpoints_per_s,min_mpoints_per_s,max_mpoints_per_s,median_mb_per_s" > "$load_csv"
echo "small_points,large_points,vertices,runs,small_median_s,small_min_s,small_max_s,large_median_s,large_min_s,large_max_s,ratio_median,ratio_min,ratio_max" > "$pair_csv"

load_start=$(cut -d' ' -f1-3 /proc/loadavg)
started=$(date +%s)
log=$(mktemp)
trap 'rm -f "$log"' EXIT

for n in 1000 10000 30000; do
  "$bin" output --cloud "$cloud" --vertices "$n" --points "$base" --runs "$runs" --csv "$out_csv" | tee -a "$log"
done
for n in $dense_sizes; do
  r=$runs
  if [[ $n == 1000000 ]]; then r=$runs_largest; fi
  "$bin" output --cloud "$cloud" --vertices "$n" --points "$dense" --runs "$r" --csv "$out_csv" | tee -a "$log"
done
for p in $input_points; do
  "$bin" input --cloud "$cloud" --vertices 30000 --points "$p" --runs "$runs" --csv "$in_csv" | tee -a "$log"
done
# The input target's ratio, from alternating runs of the smallest and the largest cloud.
"$bin" pair --cloud "$cloud" --vertices 30000 --points "${input_points##* }" --runs "$runs" --csv "$pair_csv" | tee -a "$log"
"$bin" loading --cloud "$cloud" --points "$dense" --runs "$(( runs > 5 ? runs : 5 ))" --csv "$load_csv" | tee -a "$log"
load_end=$(cut -d' ' -f1-3 /proc/loadavg)
minutes=$(( ($(date +%s) - started + 30) / 60 ))

# c(n): n with thousands separators, for the awk programs below.
awk_commas='function c(n,   s) { s = sprintf("%d", n); while (s ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]($|,)/, ",&", s); return s }'

command="bench/run_scaling.sh"
if (( quick )); then command+=" --quick"; fi
command+=" $runs"
if [[ $runs_largest != "$runs" ]]; then command+=" $runs_largest"; fi

{
  echo "# Scaling benchmarks"
  echo
  echo "Command: \`$command\` (Release, one thread; about $minutes minutes). $(date -u +%Y-%m-%d)."
  echo
  echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB, $(uname -sr)."
  echo "Load average when the benchmark started: $load_start; when it ended: $load_end."
  echo
  echo "Each figure is the median of the runs given in the table (minimum and maximum in brackets), one"
  echo "process per row; default parameters (Table 2 of the paper, edge swap on, seed 1)."
  if [[ $runs_largest != "$runs" ]]; then
    echo "The 1,000,000-vertex row has $runs_largest runs, to keep the whole benchmark within reach (each such run"
    echo "takes minutes); every other row has $runs."
  fi
  if grep -q "finishing stage off" "$log"; then
    echo "The finishing stage that follows learning (\`Parameters::finish\`) is switched off: these are the"
    echo "figures of the learning algorithm."
  fi
  echo
  echo "**Clouds.** The bundled bunny (35,947 points) and the bunny upsampled k times: each point p is"
  echo "kept and followed by k - 1 points drawn uniformly (seeded, deterministic) from the triangle"
  echo "(p, (p + a)/2, (p + b)/2), a and b two of p's 6 nearest neighbours. New points are thus within"
  echo "half a neighbour distance of p, in the surface up to the sag of that chord: a denser sampling of"
  echo "the same scanned surface (bench/bench_scaling.cpp explains why plain jittered copies would not do"
  echo "for 1,000,000 vertices)."
  echo
  echo "**Time** is \`Statistics::seconds\`: learning, including the checks and the normalisation of the"
  echo "cloud and the building of its nearest-point index (*setup*, measured apart with a 4-vertex target"
  echo "whose index holds as many points), excluding the reading or generation of the cloud."
  echo "*Loop* = time - setup."
  echo
  echo "**Memory** is read from /proc/self/status (VmRSS, and VmHWM reset through /proc/self/clear_refs);"
  echo "the caller's cloud (\`PointCloud\`, 12 bytes per point) is in memory throughout and never counted."
  echo "*Input B/point*: the resident memory the engine adds per input point (its nearest-point index,"
  echo "which holds a sorted copy of the normalised points, or of a stratified sample of 64 points per"
  echo "output vertex when the cloud is denser than that, \`Parameters::index_points_per_vertex\`; the"
  echo "engine normalises its samples on the fly; the index alone per \`PointGrid::memory_bytes\` in"
  echo "brackets), measured in a forked copy of the process with a 4-vertex target whose index holds as"
  echo "many points, at the progress report \`reconstruct()\` makes when the"
  echo "learning ends. *Setup peak*: the peak while the engine is built, per input"
  echo "point (the index's temporary arrays included). *Bytes/vertex*: in the first timed run, the peak"
  echo "from the first progress report (65,536 iterations, after the engine is built) to the return of"
  echo "\`reconstruct()\`, minus the memory before the call and the input storage, divided by the vertex"
  echo "count (\`reconstruct()\` builds the output mesh, 36 bytes per vertex, after freeing the engine)."
  echo "*(peak - before)/N*: the whole call's peak above the memory before it, per output vertex, input"
  echo "storage included. Below 10,000 vertices the mesh takes under 2 MB, within the noise of the"
  echo "resident-memory counters: those per-vertex figures are in brackets and not judged; likewise the"
  echo "engine's fixed allocations dominate the per-point figure of the 35,947-point cloud."
  echo
  awk -F, "$awk_commas"'
    function lnn(n) { return n * log(n) }
    NR == 1 { next }
    { rows[NR] = $0; if ($4 == 30000) ref[$2] = $7 / lnn(30000) }
    END {
      print "## Output size"
      print ""
      print "| cloud points | vertices | runs | iterations | time s | setup s | M it/s | time/(N ln N), 30k = 1 | bytes/vertex | of which output mesh | (peak - before)/N | input B/point |"
      print "|---:|---:|---:|---:|---|---:|---|---:|---:|---:|---:|---:|"
      for (i = 2; i <= NR; i++) {
        split(rows[i], f, ",")
        bpv = sprintf(f[4] < 10000 ? "(%.0f)" : "%.0f", f[21])
        printf "| %s | %s | %d | %s | %.3f (%.3f-%.3f) | %.3f | %.3f (%.3f-%.3f) | %.3f | %s | %.0f | %.0f | %.1f (%.1f) |\n", \
          c(f[2]), c(f[4]), f[5], c(f[6]), f[7], f[8], f[9], f[13], f[10] / 1e6, f[11] / 1e6, f[12] / 1e6, \
          (f[7] / lnn(f[4])) / ref[f[2]], bpv, f[22], f[23], f[18], f[19]
      }
      print ""
      print "time/(N ln N) is normalised to the 30,000-vertex row of the same cloud."
    }' "$out_csv"
  echo
  awk -F, "$awk_commas"'
    NR == 1 { next }
    { rows[NR] = $0; if (NR == 2) { first = $7; firstloop = $14 } }
    END {
      print "## Input size (30,000 vertices)"
      print ""
      print "| cloud points | runs | time s | setup s | loop s | M it/s | time vs 36k | loop vs 36k | input B/point | setup peak B/point | bytes/vertex |"
      print "|---:|---:|---|---:|---:|---|---:|---:|---:|---:|---:|"
      for (i = 2; i <= NR; i++) {
        split(rows[i], f, ",")
        printf "| %s | %d | %.3f (%.3f-%.3f) | %.3f | %.3f | %.3f (%.3f-%.3f) | %.2f | %.2f | %.1f (%.1f) | %.1f | %.0f |\n", \
          c(f[2]), f[5], f[7], f[8], f[9], f[13], f[14], f[10] / 1e6, f[11] / 1e6, f[12] / 1e6, \
          f[7] / first, f[14] / firstloop, f[18], f[19], f[17], f[21]
      }
    }' "$in_csv"
  echo
  awk -F, "$awk_commas"'
    NR == 2 {
      print "The same two clouds as the first and last rows, timed in alternation (`bench_scaling pair`: each"
      print "large-cloud run follows a small-cloud run, and their ratio is taken pair by pair, so that the"
      print "machine'"'"'s drift from one minute to the next does not fall between the two):"
      print ""
      print "| cloud points | runs | time s | ratio per pair |"
      print "|---:|---:|---|---|"
      printf "| %s | %d | %.3f (%.3f-%.3f) | 1 |\n", c($1), $4, $5, $6, $7
      printf "| %s | %d | %.3f (%.3f-%.3f) | %.2f (%.2f-%.2f) |\n", c($2), $4, $8, $9, $10, $11, $12, $13
    }' "$pair_csv"
  echo
  echo "## Loading (read_points, warm page cache)"
  echo
  echo "| format | points | file MB | runs | time s | M points/s | MB/s |"
  echo "|---|---:|---:|---:|---|---|---:|"
  awk -F, "$awk_commas"'
    NR > 1 { printf "| %s | %s | %.1f | %d | %.4f (%.4f-%.4f) | %.1f (%.1f-%.1f) | %.0f |\n", $1, c($2), $3, $4, $5, $6, $7, $8, $9, $10, $11 }' "$load_csv"
  echo
  echo "## Targets"
  echo
  awk -F, -v dense="$dense" "$awk_commas"'
    function lnn(n) { return n * log(n) }
    function verdict(ok, miss) { return ok ? "**met**" : "**missed** (" miss ")" }
    FNR == 1 { file++; next }
    file == 1 && $2 == dense { t[$4] = $7; if ($4 > maxn) maxn = $4; if ($4 >= 10000 && $21 > bpv) { bpv = $21; bpvn = $4 } }
    file == 1 && $2 != dense && $4 >= 10000 && $21 > bpv { bpv = $21; bpvn = $4 }
    file == 2 { if (!p0) { p0 = $2; t0 = $7; l0 = $14 } pl = $2; tl = $7; ll = $14; inpp = $18 }
    file == 3 && $1 == "ply_binary" { ply = $8 }
    file == 3 && $1 == "xyz" { xyz = $8 }
    file == 4 { pair = $11; pair_lo = $12; pair_hi = $13 }
    END {
      if (maxn == 1000000)
        printf "- 1,000,000 vertices in <= 60 s: %.1f s, %s.\n", t[1000000], verdict(t[1000000] <= 60, sprintf("%.1fx the target", t[1000000] / 60))
      else
        printf "- 1,000,000 vertices in <= 60 s: not run (largest size %s).\n", c(maxn)
      # Growth: time/(N ln N) should not rise from one size to the next (dense cloud).
      n = 0; for (s in t) sizes[++n] = s + 0
      for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (sizes[j] < sizes[i]) { x = sizes[i]; sizes[i] = sizes[j]; sizes[j] = x }
      worst = 0; wa = 0; wb = 0
      for (i = 2; i <= n; i++) {
        a = sizes[i - 1]; b = sizes[i]
        rise = (t[b] / lnn(b)) / (t[a] / lnn(a)) - 1
        if (rise > worst) { worst = rise; wa = a; wb = b }
      }
      big = sizes[n]
      growth = (t[big] / t[30000]) / (lnn(big) / lnn(30000))
      printf "- Time growing no worse than N log N (dense cloud, each size against the next smaller one): %s; from 30,000 to %s vertices the time grows %.2fx as fast as N log N.\n", \
        verdict(worst <= 0, sprintf("time/(N ln N) rises by %.0f%% from %s to %s vertices", 100 * worst, c(wa), c(wb))), c(big), growth
      printf "- At most 200 bytes per mesh vertex of peak memory during learning, input excluded: largest %.0f bytes/vertex (%s vertices; rows from 10,000 vertices), %s.\n", \
        bpv, c(bpvn), verdict(bpv <= 200, sprintf("by %.0f bytes", bpv - 200))
      total = 12 + inpp
      printf "- Input points stored in 12-16 bytes each: %.1f bytes per point at %s points (the caller'"'"'s cloud, 12, plus %.1f the engine adds: the nearest-point index with its sorted copy of the points it indexes), %s.\n", \
        total, c(pl), inpp, verdict(total <= 16, sprintf("%.1fx the 16-byte bound", total / 16))
      printf "- %s-point input no more than 1.5x slower than %s-point (same 30,000-vertex output, loading excluded): %.2fx in alternating runs (%.2f-%.2f; %.2fx between the table'"'"'s rows, learning loop alone %.2fx), %s.\n", \
        c(pl), c(p0), pair, pair_lo, pair_hi, tl / t0, ll / l0, verdict(pair <= 1.5, sprintf("by %.2fx", pair - 1.5))
      printf "- Loading binary PLY >= 50 M points/s: %.1f M points/s, %s.\n", ply, verdict(ply >= 50, sprintf("%.0f%% short", 100 * (1 - ply / 50)))
      printf "- Loading XYZ text >= 5 M points/s: %.1f M points/s, %s.\n", xyz, verdict(xyz >= 5, sprintf("%.0f%% short", 100 * (1 - xyz / 5)))
    }' "$out_csv" "$in_csv" "$load_csv" "$pair_csv"
  echo
  echo "## Raw output"
  echo
  echo '```'
  cat "$log"
  echo '```'
} > "$md"
cat "$md"
