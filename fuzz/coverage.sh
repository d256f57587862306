#!/usr/bin/env bash
# make fuzz-coverage: line coverage of core/ reached by each fuzz target's corpus alone.
# The targets are built by `make fuzz-build` with clang's source-based coverage instead
# of the sanitizers (into BUILD_DIR), each runs once over fuzz/corpus/<target>/ and the
# local corpus build-fuzz/corpus/<target>/ (libFuzzer -runs=0), and llvm-cov (Debian's
# llvm-14) reports the lines of core/ run: all of core/, the intersectors
# (intersect.c, intersect_triangle.h) and the BVH (bvh.c, bvh_collapse.c, scene_query.c,
# bvh_slab.h), one row per target and backend, then one for all of a backend's targets
# together. Percentages are of the core lines linked into the binaries.
# Usage: fuzz/coverage.sh BUILD_DIR BINARY...
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1
shift
profdata=$(command -v llvm-profdata-14 || command -v llvm-profdata)
cov=$(command -v llvm-cov-14 || command -v llvm-cov)
printf '%-8s %-14s %8s %14s %8s\n' backend target "core/" "intersectors" "BVH"
# lines FILE...: the percentage of lines run in the llvm-cov report rows of FILE... (names
# as the report shows them: relative to core/)
lines() {
  awk -v files="$*" 'BEGIN { n = split(files, f, " "); for (i = 1; i <= n; i++) want[f[i]] = 1 }
    want[$1] { total += $8; missed += $9 }
    END { if (total) printf "%.1f%%", 100 * (total - missed) / total; else printf "-" }' "$report"
}
for bin in "$@"; do
  name=$(basename "$bin") variant=$(basename "$(dirname "$bin")")
  dir=$build/profile/$variant/$name
  rm -rf "$dir"
  mkdir -p "$dir"
  corpora=("fuzz/corpus/$name")
  [ -d "build-fuzz/corpus/$name" ] && corpora+=("build-fuzz/corpus/$name")
  LLVM_PROFILE_FILE="$dir/%p.profraw" "$bin" -runs=0 -timeout=60 "${corpora[@]}" >"$dir/log" 2>&1 ||
    { echo "$variant $name: the corpus run failed ($dir/log)"; continue; }
  "$profdata" merge -sparse "$dir"/*.profraw -o "$dir/merged.profdata"
  report=$dir/report.txt
  "$cov" report "$bin" -instr-profile="$dir/merged.profdata" core/*.c core/*.h >"$report" 2>/dev/null
  printf '%-8s %-14s %8s %14s %8s\n' "$variant" "$name" "$(lines $(cd core && echo *.c *.h))" \
    "$(lines intersect.c intersect_triangle.h)" "$(lines bvh.c bvh_collapse.c scene_query.c bvh_slab.h)"
done
# The union per backend: every target's profile against all its binaries.
for variant in $(for b in "$@"; do basename "$(dirname "$b")"; done | sort -u); do
  bins=() objects=()
  for b in "$@"; do [ "$(basename "$(dirname "$b")")" = "$variant" ] && bins+=("$b") objects+=(-object "$b"); done
  dir=$build/profile/$variant
  "$profdata" merge -sparse "$dir"/*/*.profraw -o "$dir/all.profdata"
  report=$dir/all.txt
  "$cov" report "${objects[@]:1}" -instr-profile="$dir/all.profdata" core/*.c core/*.h >"$report" 2>/dev/null
  printf '%-8s %-14s %8s %14s %8s\n' "$variant" "(all targets)" "$(lines $(cd core && echo *.c *.h))" \
    "$(lines intersect.c intersect_triangle.h)" "$(lines bvh.c bvh_collapse.c scene_query.c bvh_slab.h)"
done
