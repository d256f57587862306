#!/usr/bin/env bash
# Runs a command built with ASan+UBSan and fails if any sanitizer report was written,
# even by a child process whose exit status was swallowed (Criterion forks per test
# and counts a test whose child leaked at exit as passed).
# Usage: fuzz/sanitized.sh REPORT_DIR COMMAND [ARG...]
set -uo pipefail
reports=$1
shift
rm -rf "$reports"
mkdir -p "$reports"
reports=$(cd "$reports" && pwd)
# Same log_path for both: with both runtimes linked, the last one parsed wins.
log=log_path=$reports/report
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:$log${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:$log${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
"$@"
status=$?
if compgen -G "$reports/report.*" >/dev/null; then
    echo "sanitizer reports:" >&2
    cat "$reports"/report.* >&2
    exit 1
fi
if [ $status != 0 ]; then
    echo "$1 exited with status $status" >&2
    exit $status
fi
echo "no sanitizer reports"
