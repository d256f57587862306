#!/usr/bin/env bash
# The bad-input catalogue: runs every case of tests/bad/cases.txt and checks that rtk
# answers it as the case says: the exit code; exactly one line on stderr, containing
# the expected text (nothing for exit 0); no crash (signal) or sanitizer report; no
# hang; and nothing left behind (each case runs in a fresh copy of its folder with an
# empty $OUT, and both must end as they began: no output, no temporary file).
#   tests/bad/run.sh [--valgrind] [RTK]    RTK defaults to build/rtk
# --valgrind runs rtk under memcheck and also wants 0 errors and 0 bytes lost.
# Cases that need a file to be unreadable run as nobody when this runs as root (root
# reads anything), or are skipped with the reason when setpriv is missing or nobody
# may not run RTK.
# Ends with "bad-inputs: N passed, M failed"; exits 1 when M > 0.
set -euo pipefail

valgrind=0
if [ "${1:-}" = --valgrind ]; then valgrind=1; shift; fi
here=$(cd "$(dirname "$0")" && pwd)
rtk=$(realpath "${1:-$here/../../build/rtk}")
[ -x "$rtk" ] || { echo "bad-inputs: no rtk binary at $rtk" >&2; exit 2; }

if [ $valgrind = 1 ]; then
  timeout=600 interrupt_after=30
  wrap=(valgrind --log-fd=9 --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=all
        --show-leak-kinds=all)
else
  timeout=10 interrupt_after=2 wrap=()
fi

tmp=$(mktemp -d)
chmod 755 "$tmp" # nobody must reach the case folders
trap 'chmod -R u+rwX "$tmp"; rm -rf "$tmp"' EXIT

# Prints why the valgrind log $1 is not clean, or nothing.
valgrind_problem() {
  grep -q 'ERROR SUMMARY: 0 errors' "$1" || { grep -m1 'ERROR SUMMARY' "$1" || echo "no ERROR SUMMARY"; return; }
  grep -q 'All heap blocks were freed' "$1" && return
  local kind
  for kind in 'definitely lost' 'indirectly lost' 'possibly lost' 'still reachable'; do
    grep -q "$kind: 0 bytes" "$1" || { grep -m1 "$kind" "$1" || echo "no '$kind' line"; }
  done
}

# Runs case $1 (see cases.txt for the fields); prints one line; returns 1 on failure.
run_case() {
  local name=$1 folder=$2 setup=$3 want=$4 message=$5 args=$6
  local work=$tmp/$name
  mkdir -p "$work/out"
  cp -R "$here/$folder" "$work/case"
  local prefix=() drop=0
  case $setup in
    unreadable:*) chmod 000 "$work/case/${setup#unreadable:}"; drop=1 ;;
    readonly-out) chmod 555 "$work/out"; drop=1 ;;
    interrupt) prefix=(timeout --preserve-status -s INT "$interrupt_after") ;;
  esac
  if [ $drop = 1 ] && [ "$(id -u)" = 0 ]; then
    if ! command -v setpriv >/dev/null; then
      echo "skip  $name: running as root, whom permissions do not stop, and setpriv is missing"
      return 2
    fi
    chown -R nobody: "$work"
    prefix=(setpriv --reuid=nobody --regid="$(id -gn nobody)" --clear-groups)
    if ! "${prefix[@]}" test -x "$rtk"; then
      echo "skip  $name: running as root, and nobody may not run $rtk"
      return 2
    fi
  fi
  (cd "$work" && find . | sort) >"$tmp/$name.before"
  local argv=()
  read -ra argv <<<"${args//\$OUT/$work/out}"
  local rc=0
  (cd "$work/case" && timeout -k 5 "$timeout" "${prefix[@]}" "${wrap[@]}" "$rtk" "${argv[@]}" \
    >"$tmp/$name.stdout" 2>"$tmp/$name.stderr" 9>"$tmp/$name.valgrind") || rc=$?
  local err=$tmp/$name.stderr why=""
  if [ $rc = 124 ] || [ $rc = 137 ]; then why="no answer within ${timeout}s (hang)"
  elif [ $rc -ge 128 ]; then why="crashed with signal $((rc - 128))"
  elif grep -qE 'Sanitizer|runtime error:' "$err"; then why="sanitizer report"
  elif [ "$rc" != "$want" ]; then why="exit code $rc, expected $want"
  elif [ "$want" = 0 ] && [ -s "$err" ]; then why="expected nothing on stderr"
  elif [ "$want" != 0 ] && { [ "$(wc -l <"$err")" != 1 ] || [ -n "$(tail -c 1 "$err")" ]; }; then
    why="stderr is $(wc -l <"$err") lines, expected exactly 1"
  elif [ "$want" != 0 ] && ! grep -qF -- "$message" "$err"; then why="stderr lacks '$message'"
  fi
  chmod -R u+rwX "$work"
  local left
  left=$(cd "$work" && find . | sort | comm -13 "$tmp/$name.before" -)
  if [ -z "$why" ] && [ -n "$left" ]; then why="left behind: ${left//$'\n'/ }"; fi
  if [ -z "$why" ] && [ $valgrind = 1 ]; then why=$(valgrind_problem "$tmp/$name.valgrind" | tr -s ' \n' ' '); fi
  if [ -n "$why" ]; then
    echo "FAIL  $name: $why"
    sed 's/^/        stderr: /' "$err" | head -5
    return 1
  fi
  local memcheck=""
  if [ $valgrind = 1 ]; then
    memcheck=" [memcheck: $(sed -n 's/.*total heap usage: //p' "$tmp/$name.valgrind"), 0 errors, 0 lost]"
  fi
  echo "pass  $name: $(head -c 160 "$err")$memcheck"
}

trim() { local s=$1; s=${s#"${s%%[![:space:]]*}"}; echo "${s%"${s##*[![:space:]]}"}"; }

passed=0 failed=0 skipped=0
while IFS='|' read -r name folder setup want message args; do
  case $name in ''|'#'*) continue ;; esac
  rc=0
  run_case "$(trim "$name")" "$(trim "$folder")" "$(trim "$setup")" "$(trim "$want")" "$(trim "$message")" \
    "$(trim "$args")" || rc=$?
  case $rc in 0) passed=$((passed + 1)) ;; 2) skipped=$((skipped + 1)) ;; *) failed=$((failed + 1)) ;; esac
done <"$here/cases.txt"
[ $skipped = 0 ] || echo "bad-inputs: $skipped skipped (see above)"
echo "bad-inputs: $passed passed, $failed failed"
[ $failed = 0 ]
