#!/usr/bin/env bash
# The bad-input catalogue: runs every case of tests/bad/cases.txt and checks that rtk
# answers it as the case says: the exit code; exactly one line on stderr, containing
# the expected text (nothing for exit 0); no crash (signal) or sanitizer report; no
# hang; nothing touched or left behind (each case runs in a fresh copy of its folder
# with an empty $OUT, and both must end as they began: the same files, with the same
# sizes, modes, inodes and times -- no output, no temporary file, no replaced input);
# /dev/null and /dev/full still character devices; and, in a native build, a peak RSS
# within --max-memory plus a fixed baseline when the case gives --max-memory.
#   tests/bad/run.sh [--valgrind] [RTK]    RTK defaults to build/rtk
# BAD_CASES=REGEX runs only the cases whose name matches (a bash regular expression).
# The build is told from `rtk --version` (double or fixed) and from its symbols (ASan);
# cases tagged [double], [fixed] or [native] (not under ASan or valgrind) run only there.
# --valgrind runs rtk under memcheck and also wants 0 errors and 0 bytes lost.
# Cases that need a file to be unreadable run as nobody when this runs as root (root
# reads anything), through setpriv; without setpriv they fail: they cannot be tested.
# Ends with "bad-inputs: N passed, M failed"; exits 1 when M > 0.
set -euo pipefail
export LC_ALL=C

valgrind=0
if [ "${1:-}" = --valgrind ]; then valgrind=1; shift; fi
here=$(cd "$(dirname "$0")" && pwd)
rtk=$(realpath "${1:-$here/../../build/rtk}")
[ -x "$rtk" ] || { echo "bad-inputs: no rtk binary at $rtk" >&2; exit 2; }

case $("$rtk" --version 2>/dev/null) in
  *"fixed build"*) build=fixed ;;
  *"double build"*) build=double ;;
  *) echo "bad-inputs: cannot tell the build of $rtk from --version" >&2; exit 2 ;;
esac
native=1
# grep reads all of nm's output: with -q it would stop early and pipefail would see SIGPIPE.
if [ $valgrind = 1 ] || nm "$rtk" 2>/dev/null | grep __asan_init >/dev/null; then native=0; fi
echo "bad-inputs: $rtk, $build build, $([ $native = 1 ] && echo native || echo sanitized)"

if [ $valgrind = 1 ]; then
  timeout=600 slow=15
  wrap=(valgrind --log-fd=9 --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=all
        --show-leak-kinds=all)
else
  timeout=10 slow=1 wrap=()
fi
# Peak RSS may exceed --max-memory by this much: the binary, libraries, stacks and
# malloc's overhead, which rtk does not count (docs/robustness.md).
rss_baseline_kib=$((32 * 1024))

tmp=$(mktemp -d)
chmod 755 "$tmp" # nobody must reach the case folders
trap 'chmod -R u+rwX "$tmp"; rm -rf "$tmp"' EXIT
if [ $native = 1 ]; then
  cc -O2 -o "$tmp/peak_rss" "$here/peak_rss.c" || { echo "bad-inputs: cannot build peak_rss" >&2; exit 2; }
fi
# A copy nobody can run when RTK sits in a folder nobody may enter (a private home).
rtk_for_nobody=$rtk

# Prints why the valgrind log $1 is not clean, or nothing. A process stopped by a
# signal ($2 = 6) may end in its handler (_exit, see platform/cli/signals.h) with its
# memory still held: then only errors and lost blocks count.
valgrind_problem() {
  grep -q 'ERROR SUMMARY: 0 errors' "$1" || { grep -m1 'ERROR SUMMARY' "$1" || echo "no ERROR SUMMARY"; return; }
  grep -q 'All heap blocks were freed' "$1" && return
  local kind kinds=('definitely lost' 'indirectly lost' 'possibly lost' 'still reachable')
  [ "$2" != 6 ] || kinds=('definitely lost' 'indirectly lost')
  for kind in "${kinds[@]}"; do
    grep -q "$kind: 0 bytes" "$1" || { grep -m1 "$kind" "$1" || echo "no '$kind' line"; }
  done
}

# Every file below $1 with its type, mode and inode, and for regular files size and time:
# a replaced, rewritten, created or removed file shows (a FIFO read or written does not).
snapshot() {
  (cd "$1" && find . \( -type f -printf '%p %y %m %i %s %T@\n' \) -o -printf '%p %y %m %i -> %l\n' | sort)
}

# KiB in a --max-memory value (K, M or G suffix), or nothing when $1 has none.
max_memory_kib() {
  local args=$1 v
  [[ $args =~ --max-memory\ ([0-9]+)([KkMmGg]?) ]] || return 0
  v=${BASH_REMATCH[1]}
  case ${BASH_REMATCH[2]} in
    K|k) echo "$v" ;; M|m) echo $((v * 1024)) ;; G|g) echo $((v * 1024 * 1024)) ;; *) echo $((v / 1024)) ;;
  esac
}

# Sets up case $name in $work from the comma-separated setup words (see cases.txt).
# Sets drop, the stdin/stdout redirections, the signal and ignore prefixes.
prepare() {
  local word f a b
  IFS=',' read -ra words <<<"$setup"
  for word in "${words[@]}"; do
    IFS=':' read -r kind a b <<<"$word"
    case $kind in
      -) ;;
      unreadable) chmod 000 "$work/case/$a"; drop=1 ;;
      readonly-out) chmod 555 "$work/out"; drop=1 ;;
      readonly-file) echo "not an image" >"$work/case/$a"; chmod 444 "$work/case/$a"; drop=1 ;;
      fifo) mkfifo "$work/case/$a" ;;
      fifo-reader) mkfifo "$work/case/$a"; exec {reader}<>"$work/case/$a" ;;
      symlink) ln -s "$b" "$work/case/$a" ;;
      hardlink) ln "$work/case/$b" "$work/case/$a" ;;
      sparse) truncate -s "$b" "$work/case/$a" ;;
      gen) (cd "$work/case" && "./$a") ;;
      stdin) stdin=$work/case/$a ;;
      stdin-pipe) stdin=pipe:$work/case/$a ;;
      stdin-late) stdin=late:$b:$work/case/$a ;;
      stdin-hang) mkfifo "$tmp/$name.hang"; exec {hang}<>"$tmp/$name.hang"; stdin=/dev/fd/$hang ;;
      stdout-full) stdout=/dev/full ;;
      signal) signal=(timeout --preserve-status -s "$a" "$((b * slow))") ;;
      ignore) ignore=(env --ignore-signal="$a") ;;
      timeout) case_timeout=$a ;;
      *) echo "bad-inputs: $name: unknown setup '$word'" >&2; exit 2 ;;
    esac
  done
}

# Runs case $1 (see cases.txt for the fields); prints one line; returns 1 on failure.
run_case() {
  local name=$1 folder=$2 setup=$3 want=$4 message=$5 args=$6
  local work=$tmp/$name drop=0 stdin=/dev/null stdout=$tmp/$name.stdout case_timeout=$timeout
  local signal=() ignore=() prefix=() rss=() reader="" hang="" words=() kind
  mkdir -p "$work/out"
  cp -R "$here/$folder" "$work/case"
  prepare
  local run_rtk=$rtk
  if [ $drop = 1 ] && [ "$uid" = 0 ]; then
    if ! command -v setpriv >/dev/null; then
      echo "FAIL  $name: running as root, whom permissions do not stop, and setpriv is missing: cannot test"
      return 1
    fi
    if [ "$rtk_for_nobody" = "$rtk" ] && ! setpriv --reuid=nobody --regid="$(id -gn nobody)" --clear-groups \
      test -x "$rtk"; then
      rtk_for_nobody=$tmp/rtk
      cp "$rtk" "$rtk_for_nobody"
      chmod 755 "$rtk_for_nobody"
    fi
    run_rtk=$rtk_for_nobody
    chown -R nobody: "$work"
    prefix=(setpriv --reuid=nobody --regid="$(id -gn nobody)" --clear-groups)
  fi
  if [ $native = 1 ]; then rss=("$tmp/peak_rss" "$tmp/$name.rss"); fi
  snapshot "$work" >"$tmp/$name.before"
  local argv=()
  read -ra argv <<<"${args//\$OUT/$work/out}"
  local checker=("${wrap[@]}")
  # Ended by a signal handler's _exit, memory is still held: only lost blocks are errors.
  [ "$want" != 6 ] || checker=("${checker[@]/--errors-for-leak-kinds=all/--errors-for-leak-kinds=definite,indirect}")
  local rc=0 command=(timeout -k 5 "$case_timeout" "${signal[@]}" "${rss[@]}" "${prefix[@]}" "${ignore[@]}"
                      "${checker[@]}" "$run_rtk" "${argv[@]}")
  case $stdin in
    pipe:*) (cd "$work/case" && "${command[@]}" 0< <(cat "${stdin#pipe:}") \
               >"$stdout" 2>"$tmp/$name.stderr" 9>"$tmp/$name.valgrind") || rc=$? ;;
    late:*) local rest=${stdin#late:}
            (cd "$work/case" && "${command[@]}" 0< <(sleep "${rest%%:*}"; cat "${rest#*:}") \
               >"$stdout" 2>"$tmp/$name.stderr" 9>"$tmp/$name.valgrind") || rc=$? ;;
    *) (cd "$work/case" && "${command[@]}" <"$stdin" >"$stdout" 2>"$tmp/$name.stderr" 9>"$tmp/$name.valgrind") \
         || rc=$? ;;
  esac
  [ -z "$reader" ] || exec {reader}>&-
  [ -z "$hang" ] || exec {hang}>&-
  local err=$tmp/$name.stderr why="" kib="" cap=""
  [ -s "$tmp/$name.rss" ] && read -r kib <"$tmp/$name.rss"
  cap=$(max_memory_kib "$args")
  if [ $rc = 124 ] || [ $rc = 137 ]; then why="no answer within ${case_timeout}s (hang)"
  elif [ $rc -ge 128 ]; then why="crashed with signal $((rc - 128))"
  elif grep -qE 'Sanitizer|runtime error:' "$err"; then why="sanitizer report"
  elif [ "$rc" != "$want" ]; then why="exit code $rc, expected $want"
  elif [ "$want" = 0 ] && [ -s "$err" ]; then why="expected nothing on stderr"
  elif [ "$want" != 0 ] && { [ "$(wc -l <"$err")" != 1 ] || [ -n "$(tail -c 1 "$err")" ]; }; then
    why="stderr is $(wc -l <"$err") lines, expected exactly 1"
  elif [ "$want" != 0 ] && ! grep -qF -- "$message" "$err"; then why="stderr lacks '$message'"
  elif [ -n "$cap" ] && [ -n "$kib" ] && [ "$kib" -gt $((cap + rss_baseline_kib)) ]; then
    why="peak RSS $kib KiB, over --max-memory ($cap KiB) plus $rss_baseline_kib KiB"
  elif ! [ -c /dev/null ] || ! [ -c /dev/full ]; then why="/dev/null or /dev/full is no longer a character device"
  fi
  local changed
  changed=$(snapshot "$work" | comm -3 "$tmp/$name.before" - | tr -s '\t' ' ') || true
  [ $drop = 0 ] || chmod -R u+rwX "$work"
  if [ -z "$why" ] && [ -n "$changed" ]; then why="changed or left behind: ${changed//$'\n'/ }"; fi
  if [ -z "$why" ] && [ $valgrind = 1 ]; then why=$(valgrind_problem "$tmp/$name.valgrind" "$want" | tr -s ' \n' ' '); fi
  if [ -n "$why" ]; then
    echo "FAIL  $name: $why"
    sed 's/^/        stderr: /' "$err" | head -5
    return 1
  fi
  local extra=""
  if [ -n "$cap" ] && [ -n "$kib" ]; then extra=" [peak RSS $((kib / 1024)) MiB]"; fi
  if [ $valgrind = 1 ]; then
    extra=" [memcheck: $(sed -n 's/.*total heap usage: //p' "$tmp/$name.valgrind"), 0 errors, 0 lost]"
  fi
  echo "pass  $name: $(head -c 160 "$err")$extra"
}

# Sets the variable $1 to $2 without leading and trailing blanks (no subshell: the
# catalogue's cost is mostly the processes it starts).
trim() { local s=$2; s=${s#"${s%%[![:space:]]*}"}; printf -v "$1" '%s' "${s%"${s##*[![:space:]]}"}"; }

# True when every tag of the case ("name [double native]") fits this build.
applies() {
  local tag
  for tag in $1; do
    case $tag in
      double | fixed) [ "$tag" = "$build" ] || return 1 ;;
      native) [ $native = 1 ] || return 1 ;;
      *) echo "bad-inputs: unknown tag '$tag'" >&2; exit 2 ;;
    esac
  done
}

passed=0 failed=0 other=0
uid=$(id -u)
while IFS='|' read -r name folder setup want message args; do
  case $name in ''|'#'*) continue ;; esac
  trim name "$name"
  tags=""
  if [[ $name =~ ^([^ ]+)\ *\[(.*)\]$ ]]; then name=${BASH_REMATCH[1]} tags=${BASH_REMATCH[2]}; fi
  if ! applies "$tags"; then other=$((other + 1)); continue; fi
  if [ -n "${BAD_CASES:-}" ] && ! [[ $name =~ $BAD_CASES ]]; then continue; fi
  for field in folder setup want message args; do trim "$field" "${!field}"; done
  if run_case "$name" "$folder" "$setup" "$want" "$message" "$args"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
  fi
done <"$here/cases.txt"
echo "bad-inputs: $passed passed, $failed failed ($other lines are for other builds)"
[ $failed = 0 ]
