#!/usr/bin/env bash
# make fuzz-long: explores with fresh random seeds and keeps what it learns. Each target
# runs SECONDS per backend, starting from fuzz/corpus/<target>/ and the local corpus
# BUILD_DIR/corpus/<target>/; then both are minimised (libFuzzer -merge=1 with every
# backend's binary): the named seeds (regression inputs) stay, the local corpus keeps
# what adds any feature, fuzz/corpus/<target>/ (committed) what adds an edge. Every run appends one line to fuzz/long-runs.txt,
# the running total that docs/robustness.md reports (fuzz/long.sh --totals sums it).
# Usage: fuzz/long.sh BUILD_DIR SECONDS JOBS BINARY...     (JOBS targets at a time)
#        fuzz/long.sh --totals
# Exits 1 if any run found a crash or broken invariant; its input and log stay in
# BUILD_DIR/long/<backend>/<target>/.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=fuzz/long-runs.txt

if [ "${1:-}" = --totals ]; then
  awk '!/^#/ && NF >= 6 { k = $3 " " $2; s[k] += $4; e[k] += $5; n[k]++ }
       END { for (k in s) printf "%-26s %4d runs %9.2f CPU-hours %14d execs\n", k, n[k], s[k] / 3600, e[k] }' "$runs" | sort -k2,2 -k1,1
  exit 0
fi

if [ "${1:-}" = --one ]; then # --one BUILD SECONDS TARGET BINARY...: every backend of one target
  build=$2 seconds=$3 name=$4
  shift 4
  status=0 dirs=()
  for bin in "$@"; do
    variant=$(basename "$(dirname "$bin")")
    dir=$build/long/$variant/$name
    rm -rf "$dir"
    mkdir -p "$dir/corpus"
    cp fuzz/corpus/"$name"/* "$dir/corpus/" 2>/dev/null || true
    cp "$build/corpus/$name"/* "$dir/corpus/" 2>/dev/null || true
    dict=()
    [ -f "fuzz/dict/$name.dict" ] && dict=(-dict="fuzz/dict/$name.dict")
    seed=$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')
    verdict=ok
    # CPU seconds (user + system) of the run, which is what the totals add up.
    TIMEFORMAT='%R %U %S'
    { time "$bin" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1 -seed="$seed" \
      -artifact_prefix="$dir/" "${dict[@]}" "$dir/corpus" >"$dir/log" 2>&1 || verdict=FAILED; } 2>"$dir/time"
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log")
    took=$(awk '{ printf "%d", $2 + $3 }' "$dir/time")
    cov=$(grep -o 'cov: [0-9]*' "$dir/log" | tail -1 | tr -d 'cov: ' || true)
    printf '%s %s %s %s %s %s %s %s\n' "$(date -u +%FT%TZ)" "$variant" "$name" "${took:-$seconds}" "${execs:-0}" \
      "${cov:-?}" "$seed" "$verdict" >>"$runs"
    printf '%-8s %-14s %10s execs  cov %-6s seed %-10s %s\n' "$variant" "$name" "${execs:-?}" "${cov:-?}" "$seed" "$verdict"
    if [ $verdict != ok ]; then
      grep -v '^#' "$dir/log" | tail -40 | sed 's/^/    /'
      echo "    log and input: $dir"
      status=1
    fi
    dirs+=("$dir/corpus")
  done
  # Minimise twice, named seeds first each time: the local corpus keeps every input that
  # adds a feature (edges and their hit counts); the committed one only those that add
  # an edge (-use_counters=0), which keeps fuzz/corpus/ small.
  local_corpus=$build/corpus/$name
  mkdir -p "$local_corpus" "fuzz/corpus/$name"
  for set in local committed; do
    keep=$build/long/merged-$set-$name
    rm -rf "$keep"
    mkdir -p "$keep"
    find "fuzz/corpus/$name" -type f ! -regex '.*/[0-9a-f]\{40\}' -exec cp {} "$keep/" \;
    counters=(); from=("fuzz/corpus/$name" "$local_corpus" "${dirs[@]}")
    [ $set = committed ] && counters=(-use_counters=0) from=("$local_corpus")
    for bin in "$@"; do
      "$bin" -merge=1 -timeout=30 -rss_limit_mb=2048 "${counters[@]}" "$keep" "${from[@]}" >"$keep.log" 2>&1 ||
        { echo "    merge with $bin failed: $keep.log"; status=1; }
    done
    [ $status = 0 ] || break
    target=$local_corpus; [ $set = committed ] && target=fuzz/corpus/$name
    rm -rf "$target"
    mv "$keep" "$target"
  done
  [ $status = 0 ] && echo "         $name: corpus $(find "fuzz/corpus/$name" -type f | wc -l) files," \
    "$(du -sk --apparent-size "fuzz/corpus/$name" | cut -f1) KiB (local: $(find "$local_corpus" -type f | wc -l) files)"
  exit $status
fi

build=$1 seconds=$2 jobs=$3
shift 3
[ -f "$runs" ] || echo "# UTC-time backend target seconds executions coverage-edges seed verdict (fuzz/long.sh)" >"$runs"
names=$(for b in "$@"; do basename "$b"; done | sort -u)
failed=0
for name in $names; do
  bins=()
  for b in "$@"; do [ "$(basename "$b")" = "$name" ] && bins+=("$b"); done
  echo "$name ${bins[*]}"
done | xargs -P "$jobs" -L 1 "$0" --one "$build" "$seconds" || failed=1
echo "corpus: $(du -sk --apparent-size fuzz/corpus | cut -f1) KiB in fuzz/corpus/"
[ $failed = 0 ] || { echo "fuzz-long: at least one target failed (see above)" >&2; exit 1; }
echo "fuzz-long: every target ran ${seconds}s per backend without a finding"
