#!/usr/bin/env bash
# The rtk command built for wasm32-wasi, run under node's WASI, against native build/rtk:
# every scene of tests/golden/scenes.txt (double options) must give the same render hash
# in both, and the hash pinned in tests/golden/double.sha256.
#   web/test/cli_hashes.sh [SCENE_FILTER]    (a grep pattern on the scenes.txt lines)
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
corpus=$(cd "${RTK_SHARED:-$here/../shared}/cse457/assets/trace" && pwd)
filter=${1:-.}
pass=0 fail=0
while read -r scene opts; do
  case $scene in ''|'#'*) continue ;; esac
  echo "$scene" | grep -q -- "$filter" || continue
  opts=$(echo ${opts//@fixed-small/})
  path=${scene/#corpus\//$corpus/}
  [ "$path" = "$scene" ] && path=$here/$scene
  # shellcheck disable=SC2086
  native=$("$here/build/rtk" render "$path" --hash --quiet $opts)
  start=$(date +%s%N)
  # shellcheck disable=SC2086
  wasm=$(node --no-warnings --single-threaded "$here/web/test/wasi_run.mjs" "$here/build-web/rtk-cli.wasm" render "$path" --hash --quiet $opts) || wasm="(failed: $?)"
  ms=$((($(date +%s%N) - start) / 1000000))
  want=$(awk -v k="$scene${opts:+ $opts}" '{h=$1; $1=""; sub(/^ +/, ""); if ($0 == k) print h}' "$here/tests/golden/double.sha256")
  if [ "$wasm" = "$native" ] && [ "$native" = "$want" ]; then
    pass=$((pass + 1)); printf 'same  %s  %s  (wasm %d.%03d s)\n' "$wasm" "$scene" $((ms / 1000)) $((ms % 1000))
  else
    fail=$((fail + 1)); printf 'DIFF  %s: wasm %s, native %s, golden %s\n' "$scene" "$wasm" "$native" "$want"
  fi
done <"$here/tests/golden/scenes.txt"
echo "wasm-cli-hashes: $pass passed, $fail failed"
[ $fail = 0 ]
