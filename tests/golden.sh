#!/usr/bin/env bash
# Render hashes against tests/golden/<name>.sha256.
#   tests/golden.sh check RTK NAME [extra rtk options]   verify (exit 1 on any mismatch)
#   tests/golden.sh bless RTK NAME                       rewrite the golden file
# RTK is the rtk binary, NAME the golden set (double or fixed). Scenes are listed in
# tests/golden/scenes.txt. Extra options (e.g. --threads 7 --tile 16) must not change
# any hash: that is what check-determinism uses them for.
set -euo pipefail
mode=$1 rtk=$2 name=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
corpus=${RTK_SHARED:-$here/../../shared}/cse457/assets/trace
golden=$here/golden/$name.sha256
out=$(mktemp)
trap 'rm -f "$out"' EXIT
fail=0 count=0 bad=0
while read -r scene opts; do
  case $scene in ''|'#'*) continue ;; esac
  count=$((count + 1))
  if [ "$name" = fixed ]; then opts=${opts//@fixed-small/--width 128 --height 128}; else opts=${opts//@fixed-small/}; fi
  opts=$(echo $opts)
  path=${scene/#corpus\//$corpus/}
  [ "$path" = "$scene" ] && path=$here/../$scene
  # shellcheck disable=SC2086
  hash=$("$rtk" render "$path" --hash --quiet $opts "$@") || { echo "golden: $scene: rtk failed" >&2; fail=1 bad=$((bad + 1)); continue; }
  key="$scene${opts:+ $opts}"
  printf '%s  %s\n' "$hash" "$key" >>"$out"
  if [ "$mode" = check ]; then
    want=$(awk -v k="$key" '{h=$1; $1=""; sub(/^ +/, ""); if ($0 == k) print h}' "$golden")
    if [ -z "$want" ]; then echo "golden: $key: no golden hash in $golden" >&2; fail=1 bad=$((bad + 1))
    elif [ "$want" != "$hash" ]; then echo "golden: $key: got $hash, want $want" >&2; fail=1 bad=$((bad + 1))
    fi
  fi
done <"$here/golden/scenes.txt"
if [ "$mode" = bless ]; then
  [ $fail = 0 ] || { echo "golden: not blessed: a render failed" >&2; exit 1; }
  cp "$out" "$golden"
  echo "golden: wrote $count hashes to $golden"
  exit 0
fi
echo "golden-$name: $((count - bad)) passed, $bad failed"
exit $fail
