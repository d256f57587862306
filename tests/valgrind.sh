#!/usr/bin/env bash
# make check-valgrind: memcheck over (a) a heavy render, tests/valgrind/heavy.yaml (a
# corpus mesh after 3 Loop subdivisions, glass and mirrors to depth 10, 4 samples per
# pixel, PNG output, 2 threads), whose image must also equal the native render's,
# (b) every case of the bad-input catalogue (tests/bad/run.sh --valgrind), and (c) when
# FIXED_RTK is given, the same heavy render at 100x75 by the fixed build. (a) runs on one
# core, (b) then (c) on the other: memcheck runs one thread at a time. Every run must
# end with 0 errors and 0 bytes lost in every leak category.
#   tests/valgrind.sh [RTK [FIXED_RTK]]   RTK defaults to build/rtk; logs go to build/valgrind/
# Ends with "valgrind: N passed, M failed"; exits 1 when M > 0.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
rtk=$(realpath "${1:-$here/../build/rtk}")
fixed_rtk=${2:+$(realpath "$2")}
assets=${RTK_SHARED:-$here/../../shared}/cse457
mkdir -p "$here/../build/valgrind"
logs=$(cd "$here/../build/valgrind" && pwd)
rm -f "$logs"/heavy*.*
heavy=("$here/valgrind/heavy.yaml" --assets "$assets" --aa 1 --threads 2 --quiet)

# heavy NAME RTK WIDTH HEIGHT: the heavy render under memcheck; writes NAME.rc and NAME.want.
heavy() {
  local name=$1 bin=$2 size=(--width "$3" --height "$4") rc=0
  "$bin" render "${heavy[@]}" "${size[@]}" --hash >"$logs/$name.want"
  valgrind --log-file="$logs/$name.log" --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=all \
    --show-leak-kinds=all "$bin" render "${heavy[@]}" "${size[@]}" --hash -o "$logs/$name.png" >"$logs/$name.hash" 2>&1 || rc=$?
  echo $rc >"$logs/$name.rc"
}
# heavy_verdict NAME LABEL: prints the run's summary; returns 1 unless it was clean.
heavy_verdict() {
  local name=$1 label=$2 ok=0
  grep -E 'total heap usage|ERROR SUMMARY|lost:|reachable:|All heap blocks' "$logs/$name.log" | sed "s/^==[0-9]*== */valgrind: $label: /"
  [ "$(cat "$logs/$name.rc")" = 0 ] || { echo "valgrind: $label: exit code $(cat "$logs/$name.rc")"; ok=1; }
  grep -q 'ERROR SUMMARY: 0 errors' "$logs/$name.log" || ok=1
  grep -q 'All heap blocks were freed' "$logs/$name.log" ||
    for kind in 'definitely lost' 'indirectly lost' 'possibly lost' 'still reachable'; do
      grep -q "$kind: 0 bytes" "$logs/$name.log" || ok=1
    done
  [ "$(cat "$logs/$name.hash")" = "$(cat "$logs/$name.want")" ] || { echo "valgrind: $label: image differs from the native render"; ok=1; }
  return $ok
}

start=$SECONDS
heavy heavy "$rtk" 200 150 &
heavy_pid=$!
bad_rc=0
"$here/bad/run.sh" --valgrind "$rtk" >"$logs/bad-inputs.log" 2>&1 || bad_rc=$?
[ -z "$fixed_rtk" ] || heavy heavy-fixed "$fixed_rtk" 100 75
wait $heavy_pid || true
echo "valgrind: bad-input catalogue: $(tail -n 1 "$logs/bad-inputs.log") (log: $logs/bad-inputs.log)"
grep '^FAIL' -A5 "$logs/bad-inputs.log" || true

heavy_passed=0 heavy_failed=0
count() { if "$@"; then heavy_passed=$((heavy_passed + 1)); else heavy_failed=$((heavy_failed + 1)); fi; }
count heavy_verdict heavy "heavy render"
[ -z "$fixed_rtk" ] || count heavy_verdict heavy-fixed "heavy render, fixed build, 100x75"
echo "valgrind: took $((SECONDS - start)) s"

# The catalogue's last line, "bad-inputs: N passed, M failed" and perhaps a note after it.
passed=$(sed -n 's/^bad-inputs: \([0-9]*\) passed, \([0-9]*\) failed.*$/\1/p' "$logs/bad-inputs.log")
failed=$(sed -n 's/^bad-inputs: \([0-9]*\) passed, \([0-9]*\) failed.*$/\2/p' "$logs/bad-inputs.log")
[ -n "$passed" ] || { passed=0 failed=1; } # the catalogue did not finish
[ $bad_rc = 0 ] || [ "$failed" != 0 ] || failed=1
passed=$((passed + heavy_passed)) failed=$((failed + heavy_failed))
echo "valgrind: $passed passed, $failed failed"
[ "$failed" = 0 ]
