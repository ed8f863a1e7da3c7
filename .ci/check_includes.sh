#!/usr/bin/env bash
# The layers' include order. docs/internals.md lists the library's folders lowest first, between
# its "layers" markers, one numbered item per layer (the public headers named in an item belong
# to that layer). A file of nmesh/FOLDER/ may include only headers of its own layer or of a lower
# one; a public header nmesh/*.h only public headers of its own layer or a lower one. Each
# include that breaks the rule, and each file or include in no layer, is named; exit status 1.
#   .ci/check_includes.sh [ROOT]      check the tree at ROOT (default: this repository)
#   .ci/check_includes.sh --self-test plant upward includes in copies of the tree: each must fail
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)

check() {
  local root=$1 n=0 fail=0 line tok rel own inc key l
  declare -A level=()
  while IFS= read -r line; do
    if [[ $line =~ ^[0-9]+\.\  ]]; then n=$((n + 1)); fi
    for tok in $(grep -o '`nmesh/[^`]*`' <<< "$line" | tr -d '`'); do level[$tok]=$n; done
  done < <(sed -n '/^<!-- layers: begin/,/^<!-- layers: end/p' "$root/docs/internals.md")
  if [ "$n" -eq 0 ]; then echo "$root/docs/internals.md: no layers list"; return 1; fi
  while IFS= read -r rel; do
    if [[ $rel == nmesh/*/* ]]; then own=${level[${rel%/*}/]:-}; else own=${level[$rel]:-}; fi
    if [ -z "$own" ]; then echo "$rel: its folder or header is in no layer"; fail=1; continue; fi
    while IFS= read -r inc; do
      if [[ $inc == nmesh/*/* ]]; then
        key=${inc%/*}/
        if [[ $rel != nmesh/*/* ]]; then echo "$rel: includes $inc: a public header includes only public headers"; fail=1; continue; fi
      else
        key=$inc
      fi
      l=${level[$key]:-}
      if [ -z "$l" ]; then echo "$rel: includes $inc, which is in no layer"; fail=1
      elif [ "$l" -gt "$own" ]; then echo "$rel: includes $inc, from layer $l above its own ($own)"; fail=1; fi
    done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(nmesh\/[^"]*\)".*/\1/p' "$root/$rel")
  done < <(cd "$root" && find nmesh \( -name '*.h' -o -name '*.cpp' \) | sort)
  return $fail
}

if [ "${1:-}" = --self-test ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  # FILE and the line planted in it; each plant must fail, naming FILE.
  plants=('nmesh/learn/twist_check.cpp|#include "nmesh/pipeline/learning.h"'
          'nmesh/mesh/mesh.h|#include "nmesh/metrics.h"'
          'nmesh/reconstruct.h|#include "nmesh/learn/neural_mesh.h"'
          'nmesh/util/random.h|  #  include "nmesh/geometry/flatness.h"')
  mkdir -p "$tmp/clean/docs" && cp -r "$repo/nmesh" "$tmp/clean/" && cp "$repo/docs/internals.md" "$tmp/clean/docs/"
  check "$tmp/clean" > "$tmp/out" || { cat "$tmp/out"; echo "self-test: the tree itself fails"; exit 1; }
  for plant in "${plants[@]}"; do
    file=${plant%%|*}
    rm -rf "$tmp/tree" && cp -r "$tmp/clean" "$tmp/tree"
    echo "${plant#*|}" >> "$tmp/tree/$file"
    if check "$tmp/tree" > "$tmp/out" || ! grep -q "^$file: includes" "$tmp/out"; then
      cat "$tmp/out"; echo "self-test: the planted include in $file was not caught"; exit 1
    fi
    echo "caught: $(cat "$tmp/out")"
  done
  echo "self-test passed: ${#plants[@]} planted upward includes caught, the tree itself clean"
  exit 0
fi

root=${1:-$repo}
if check "$root"; then echo "include order: every include of nmesh/ stays at or below its layer"; else exit 1; fi
