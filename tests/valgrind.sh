#!/usr/bin/env bash
# make check-valgrind: memcheck over (a) a heavy render, tests/valgrind/heavy.yaml (a
# corpus mesh after 3 Loop subdivisions, glass and mirrors to depth 10, 4 samples per
# pixel, PNG output, 2 threads), whose image must also equal the native render's, and
# (b) every case of the bad-input catalogue (tests/bad/run.sh --valgrind). Both run at
# once: memcheck runs one thread at a time, so each takes one of two cores. Every run
# must end with 0 errors and 0 bytes lost in every leak category.
#   tests/valgrind.sh [RTK]     RTK defaults to build/rtk; logs go to build/valgrind/
# Ends with "valgrind: N passed, M failed"; exits 1 when M > 0.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
rtk=$(realpath "${1:-$here/../build/rtk}")
assets=${RTK_SHARED:-$here/../../shared}/cse457
mkdir -p "$here/../build/valgrind"
logs=$(cd "$here/../build/valgrind" && pwd)
rm -f "$logs"/heavy.*
heavy=("$here/valgrind/heavy.yaml" --assets "$assets" --aa 1 --threads 2 --quiet --width 200 --height 150)

start=$SECONDS
want=$("$rtk" render "${heavy[@]}" --hash)
valgrind --log-file="$logs/heavy.log" --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=all \
  --show-leak-kinds=all "$rtk" render "${heavy[@]}" --hash -o "$logs/heavy.png" >"$logs/heavy.hash" 2>&1 &
heavy_pid=$!
bad_rc=0
"$here/bad/run.sh" --valgrind "$rtk" >"$logs/bad-inputs.log" 2>&1 || bad_rc=$?
heavy_rc=0
wait $heavy_pid || heavy_rc=$?
echo "valgrind: bad-input catalogue: $(tail -n 1 "$logs/bad-inputs.log") (log: $logs/bad-inputs.log)"
grep '^FAIL' -A5 "$logs/bad-inputs.log" || true

heavy_ok=1
grep -E 'total heap usage|ERROR SUMMARY|lost:|reachable:|All heap blocks' "$logs/heavy.log" | sed 's/^==[0-9]*== */valgrind: heavy render: /'
[ $heavy_rc = 0 ] || { echo "valgrind: heavy render: exit code $heavy_rc"; heavy_ok=0; }
grep -q 'ERROR SUMMARY: 0 errors' "$logs/heavy.log" || heavy_ok=0
grep -q 'All heap blocks were freed' "$logs/heavy.log" ||
  for kind in 'definitely lost' 'indirectly lost' 'possibly lost' 'still reachable'; do
    grep -q "$kind: 0 bytes" "$logs/heavy.log" || heavy_ok=0
  done
[ "$(cat "$logs/heavy.hash")" = "$want" ] || { echo "valgrind: heavy render: image differs from the native render"; heavy_ok=0; }
echo "valgrind: took $((SECONDS - start)) s"

passed=$(sed -n 's/^bad-inputs: \([0-9]*\) passed, \([0-9]*\) failed$/\1/p' "$logs/bad-inputs.log")
failed=$(sed -n 's/^bad-inputs: \([0-9]*\) passed, \([0-9]*\) failed$/\2/p' "$logs/bad-inputs.log")
[ -n "$passed" ] || { passed=0 failed=1; } # the catalogue did not finish
[ $bad_rc = 0 ] || [ "$failed" != 0 ] || failed=1
if [ $heavy_ok = 1 ]; then passed=$((passed + 1)); else failed=$((failed + 1)); fi
echo "valgrind: $passed passed, $failed failed"
[ "$failed" = 0 ]
