#!/usr/bin/env bash
# Runs libFuzzer binaries for a fixed time each, JOBS at a time, every one on a
# scratch copy of fuzz/corpus/<target>/ (the repository is never written to).
# Usage: [FUZZ_SEED=N] fuzz/run.sh BUILD_DIR SECONDS JOBS BINARY...   (seed 0 or unset: random)
# Prints one line per run (executions, coverage, verdict); exits 1 if any run failed,
# leaving its log and crashing input under BUILD_DIR/run/<variant>/<target>/.
set -euo pipefail

if [ "${1:-}" = --one ]; then
    bin=$2 build=$3 seconds=$4
    name=$(basename "$bin") variant=$(basename "$(dirname "$bin")")
    dir=$build/run/$variant/$name
    rm -rf "$dir"
    mkdir -p "$dir/corpus"
    if [ -d "fuzz/corpus/$name" ]; then cp fuzz/corpus/"$name"/* "$dir/corpus/"; fi
    dict=()
    if [ -f "fuzz/dict/$name.dict" ]; then dict=(-dict="fuzz/dict/$name.dict"); fi
    status=ok
    "$bin" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -print_final_stats=1 -seed="${FUZZ_SEED:-0}" \
        -artifact_prefix="$dir/" "${dict[@]}" "$dir/corpus" >"$dir/log" 2>&1 || status=FAILED
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log")
    cov=$(grep -o 'cov: [0-9]*' "$dir/log" | tail -1 || true)
    printf '%-8s %-14s %10s execs  %-10s %s\n' "$variant" "$name" "${execs:-?}" "${cov:-}" "$status"
    if [ $status != ok ]; then
        # The finding's own message first: a long stack trace can push it out of the tail.
        grep -m 4 -A 1 -E 'invariant broken|ERROR:|runtime error' "$dir/log" | sed 's/^/    /' || true
        grep -v '^#' "$dir/log" | tail -40 | sed 's/^/    /'
        echo "    log and input: $dir"
        exit 1
    fi
    exit 0
fi

build=$1 seconds=$2 jobs=$3
shift 3
failed=0
printf '%s\n' "$@" | xargs -P "$jobs" -I{} "$0" --one {} "$build" "$seconds" || failed=1
if [ $failed != 0 ]; then
    echo "fuzz: at least one target failed (see above)" >&2
    exit 1
fi
echo "fuzz: every target ran ${seconds}s without a finding"
