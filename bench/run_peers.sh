#!/usr/bin/env bash
# nmesh against its peers: CGAL's advancing-front reconstruction (AFSR) and Open3D's screened
# Poisson surface, both benchmark-only (bench/peers/; the library never links CGAL or Open3D).
#
# Speed (bench/results/peers-speed.{md,csv}): nmesh's command-line tool and the AFSR program
# (bench/peers/afsr.cpp) timed in alternation, nmesh then AFSR, PAIRS pairs (default 7; 5 for the
# large cloud), the whole process from reading the cloud to writing the mesh (bash's clock; CPU
# time and peak memory from /usr/bin/time), default settings: the bunny, the horse and the
# corpus's diplodocus at 30,000 vertices, and a cloud of 150,000 points at 100,000 vertices. That
# cloud is drawn from the diplodocus's reference mesh (bench/resample_mesh.cpp: uniform by area,
# seed 7, Gaussian noise of 0.0005 × the diagonal, as the corpus's clouds were made), into
# build-peers/work/.
#
# Equal budget (bench/results/equal-budget.{md,csv}): at N vertices, nmesh (seeds SEEDS, default
# 1-3) against AFSR's mesh and Poisson's mesh (depth 9, normals from the 30 nearest points oriented
# by a spanning tree, vertices below the 1% density quantile removed), each decimated to N by
# quadric error (Open3D, 2N triangles: about N vertices; the actual count is reported), and
# against the reference mesh decimated the same way (the limit row, where N is at most half the
# reference's vertex count). The bunny at 2,000, 5,000 and 30,000 and every closed cloud of the
# corpus at points / 10 and points / 3. Each mesh measured by bench/mesh_distance.cpp: chamfer
# to the reference (the mean of the two directions' mean distances, 100,000 samples each way),
# the mean distance from the cloud, the share of triangles under 10 degrees.
#
#   bench/run_peers.sh                      both parts, results into bench/results/
#   bench/run_peers.sh --quick              3 pairs, no large cloud; seed 1, the bunny and two
#                                           corpus clouds; results into build-peers/quick/
#   options: --only speed|budget, --pairs N, --seeds "1 2 3", --out DIR
#
# Installs Debian's libcgal-dev, python3-open3d, python3-numpy and time if missing (as root;
# apt-get update only if the install fails without it). Needs ../shared/data and its corpus.
set -euo pipefail
cd "$(dirname "$0")/.."
command_line="bench/run_peers.sh${*:+ $*}"
data=../shared/data
quick=0
only=""
pairs=7
seeds="1 2 3"
out=bench/results
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1; pairs=3; seeds=1; out=build-peers/quick ;;
    --only) only=$2; shift ;;
    --pairs) pairs=$2; shift ;;
    --seeds) seeds=$2; shift ;;
    --out) out=$2; shift ;;
    *) echo "bench/run_peers.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
if [ ! -d "$data/corpus" ]; then echo "bench/run_peers.sh: needs $data and $data/corpus" >&2; exit 1; fi

echo "== Debian packages"
. .ci/debian_packages.sh
require_debian_packages bench/run_peers.sh libcgal-dev python3-open3d python3-numpy time
# Debian's interpreter, for which python3-open3d is built; Open3D on one thread (its OpenMP
# threads only slow a shared machine down, and no Open3D step is timed).
python=/usr/bin/python3
export OMP_NUM_THREADS=1

echo "== build: nmesh (Release), its measuring tools, the AFSR peer (build-peers/)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target nmesh_cli mesh_distance resample_mesh > /dev/null
cmake -S bench/peers -B build-peers -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build-peers -j 2 > /dev/null
nmesh=./build/nmesh
afsr=./build-peers/afsr
distance=./build/bench/mesh_distance
o3d="$python bench/peers/open3d_peers.py"
work=build-peers/work
mkdir -p "$work" "$out"

# `nmesh info`'s count of a file's points (vertices); its vertices used by a face; its topology.
points_of() { "$nmesh" info "$1" | sed -n 's/^points: //p'; }
mesh_summary() {  # FILE -> "vertices,faces,closed,boundary_loops,components"
  "$nmesh" info "$1" | awk -F': ' '
    $1 == "points" { v = $2 } $1 == "faces" { f = $2 } $1 == "vertices in no face" { u = $2 }
    $1 == "closed" { c = ($2 == "yes") } $1 == "components" { k = $2 }
    $1 == "boundary loops" { split($2, b, " "); l = b[1] }
    END { print v - u "," f "," c "," l + 0 "," k }'
}
load() { cut -d' ' -f1-3 /proc/loadavg; }

# ---- speed ----------------------------------------------------------------------------------
timed_wall=0
timed_cpu=0
timed_mib=0
timed() {  # COMMAND... : wall seconds (bash's clock), CPU seconds and peak resident MiB of one run
  local t0 t1
  t0=$EPOCHREALTIME
  /usr/bin/time -f "%M %U %S" -o "$work/time.txt" "$@" > /dev/null 2> "$work/run.log" || { cat "$work/run.log" >&2; return 1; }
  t1=$EPOCHREALTIME
  timed_wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
  timed_cpu=$(awk '{ c = $2 + $3 } END { printf "%.2f", c }' "$work/time.txt")
  timed_mib=$(awk '{ m = $1 } END { printf "%.1f", m / 1024 }' "$work/time.txt")
}
if [ "$only" != budget ]; then
  echo "== speed: nmesh and AFSR in alternation, $pairs pairs (load average $(load))"
  speed_load_start=$(load)
  cases=("$data/bunny.ply 30000" "$data/horse.ply 30000" "$data/corpus/diplodocus.ply 30000")
  if [ $quick = 0 ]; then
    large=$work/diplodocus_150k.ply
    ./build/bench/resample_mesh "$data/corpus/diplodocus_mesh.ply" 150000 "$large" --seed 7 --noise 0.0005
    cases+=("$large 100000")
  fi
  raw=$work/peers-speed.csv
  echo "cloud,points,asked,pair,program,seconds,cpu_seconds,peak_mib,vertices,faces,closed,boundary_loops,components" > "$raw"
  for c in "${cases[@]}"; do
    read -r cloud asked <<< "$c"
    name=$(basename "$cloud" .ply)
    points=$(points_of "$cloud")
    n=$pairs
    if [ "$points" -gt 100000 ] && [ "$pairs" -gt 5 ]; then n=5; fi
    for ((i = 1; i <= n; i++)); do
      timed "$nmesh" reconstruct "$cloud" -o "$work/${name}_nmesh.ply" --vertices "$asked" --quiet
      echo "$name,$points,$asked,$i,nmesh,$timed_wall,$timed_cpu,$timed_mib,$(mesh_summary "$work/${name}_nmesh.ply")" >> "$raw"
      echo "  $name pair $i: nmesh $timed_wall s ($timed_cpu s CPU), $timed_mib MiB"
      timed "$afsr" "$cloud" "$work/${name}_afsr.ply"
      echo "$name,$points,$asked,$i,afsr,$timed_wall,$timed_cpu,$timed_mib,$(mesh_summary "$work/${name}_afsr.ply")" >> "$raw"
      echo "  $name pair $i: AFSR  $timed_wall s ($timed_cpu s CPU), $timed_mib MiB"
    done
  done
  speed_load_end=$(load)
  cp "$raw" "$out/peers-speed.csv"
  {
    echo "# Speed: nmesh against the advancing front (CGAL's AFSR)"
    echo
    echo "Command: \`$command_line\` (Release). $(date -u +%Y-%m-%d), nmesh at commit $(git log -1 --format=%h -- nmesh) (its last change)."
    echo "Machine: $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -n 1), $(getconf _NPROCESSORS_ONLN) cores; load average"
    echo "$speed_load_start at the start, $speed_load_end at the end (1, 5, 15 minutes: above 1, the machine"
    echo "was shared with other work, and the alternation keeps both programs under the same load)."
    echo
    echo "Each pair runs nmesh's command-line tool (\`nmesh reconstruct CLOUD -o OUT.ply --vertices N --quiet\`,"
    echo "default settings, seed 1) and then the AFSR program (\`bench/peers/afsr.cpp\`: CGAL 5.5's"
    echo "\`advancing_front_surface_reconstruction\`, default parameters), each timed as a whole process from"
    echo "reading the cloud to writing the binary PLY: wall time by bash's clock, CPU time (user + system)"
    echo "and peak memory by /usr/bin/time. AFSR's output keeps (about) every point as a vertex;"
    echo "nmesh's has exactly N. \`diplodocus_150k\`: 150,000 points drawn from the corpus's diplodocus"
    echo "reference mesh by \`bench/resample_mesh.cpp\` (uniform by area, seed 7, Gaussian noise of"
    echo "0.0005 × the diagonal, as the corpus's clouds were made). Runs: \`peers-speed.csv\`."
    echo
    "$python" bench/peers/tables.py speed "$raw"
  } > "$out/peers-speed.md"
  cat "$out/peers-speed.md"
fi

# ---- equal budget ---------------------------------------------------------------------------
if [ "$only" != speed ]; then
  echo "== equal budget (load average $(load))"
  if [ $quick = 1 ]; then
    clouds=(bunny bull knot1)
  else
    clouds=(bunny knot1 rotor_small femur joint helmet anchor bull camel diplodocus fandisk hand triceratops)
  fi
  raw=$work/equal-budget.csv
  header=1
  : > "$raw"
  for name in "${clouds[@]}"; do
    if [ "$name" = bunny ]; then cloud=$data/bunny.ply; else cloud=$data/corpus/$name.ply; fi
    reference=${cloud%.ply}_mesh.ply
    points=$(points_of "$cloud")
    ref_vertices=$(mesh_summary "$reference" | cut -d, -f1)
    if [ "$name" = bunny ]; then budgets="2000 5000 30000"; else budgets="$((points / 10)) $((points / 3))"; fi
    "$afsr" "$cloud" "$work/${name}_afsr.ply" 2> /dev/null
    $o3d poisson "$cloud" "$work/${name}_poisson.ply" 2> /dev/null
    for n in $budgets; do
      meshes=()
      labels=()
      for s in $seeds; do
        "$nmesh" reconstruct "$cloud" -o "$work/${name}_${n}_nmesh_s$s.ply" --vertices "$n" --seed "$s" --quiet
        meshes+=("$work/${name}_${n}_nmesh_s$s.ply")
        labels+=("nmesh,$s")
      done
      for peer in afsr poisson; do
        $o3d decimate "$work/${name}_$peer.ply" "$n" "$work/${name}_${n}_${peer}_qd.ply" 2> /dev/null
        meshes+=("$work/${name}_${n}_${peer}_qd.ply")
        labels+=("${peer}_qd,")
      done
      if [ $((2 * n)) -le "$ref_vertices" ]; then
        $o3d decimate "$reference" "$n" "$work/${name}_${n}_reference_qd.ply" 2> /dev/null
        meshes+=("$work/${name}_${n}_reference_qd.ply")
        labels+=("reference_qd,")
      fi
      flag=()
      if [ $header = 1 ]; then flag=(--header); fi
      i=-$header
      while IFS= read -r line; do
        if [ $i -lt 0 ]; then
          echo "cloud,points,ref_vertices,budget,method,seed,${line#mesh,}" >> "$raw"
        else
          echo "$name,$points,$ref_vertices,$n,${labels[$i]},${line#*,}" >> "$raw"
        fi
        i=$((i + 1))
      done < <("$distance" "$cloud" "$reference" "${meshes[@]}" "${flag[@]}")
      header=0
      echo "  $name at $n: $(grep -c "^$name,[0-9]*,[0-9]*,$n," "$raw") meshes measured"
    done
  done
  cp "$raw" "$out/equal-budget.csv"
  {
    echo "# Equal budget: nmesh against standard pipelines at the same vertex count"
    echo
    echo "Command: \`$command_line\` (Release). $(date -u +%Y-%m-%d), nmesh at commit $(git log -1 --format=%h -- nmesh) (its last change)."
    echo "Seeds of nmesh: $seeds. Every mesh: \`bench/results/equal-budget.csv\`."
    echo
    echo "At N vertices: nmesh (\`nmesh reconstruct CLOUD -o OUT.ply --vertices N --seed S --quiet\`, default"
    echo "settings); AFSR + QD: CGAL's advancing front (\`bench/peers/afsr.cpp\`, default parameters) decimated"
    echo "to N by quadric error (Open3D's \`simplify_quadric_decimation\` to 2N triangles); Poisson + QD:"
    echo "Open3D's screened Poisson (depth 9, normals from the 30 nearest points oriented by a spanning"
    echo "tree, vertices under the 1% density quantile removed), decimated the same way; reference + QD:"
    echo "the reference mesh decimated the same way, the limit row, only where N is at most half its vertex"
    echo "count (\`bench/peers/open3d_peers.py\`). Chamfer: the mean of the two mean distances between the"
    echo "mesh and the reference (100,000 samples uniform by area on each, each to the other's nearest"
    echo "triangle; \`bench/mesh_distance.cpp\`); p2s: the mean distance from the cloud's points to the mesh."
    echo "Distances in units of 10⁻⁴ of the cloud's bounding-box diagonal. Ratios below 1 favour nmesh."
    echo
    "$python" bench/peers/tables.py budget "$raw"
  } > "$out/equal-budget.md"
  cat "$out/equal-budget.md"
fi
