#!/usr/bin/env bash
# BVH hashes against tests/golden/tree-<name>.sha256: the built tree of every scene
# listed there must be the same bytes (nodes, references, grid, extent) on 1 and 2
# threads as when the list was blessed. A change to the build that must keep the tree
# (a faster build) is proven by this check passing in both builds.
#   tests/tree_hash.sh check TREE_HASH NAME   verify (exit 1 on any mismatch)
#   tests/tree_hash.sh bless TREE_HASH NAME   rewrite the list: every corpus scene that
#                                             loads, scenes/bench/*.yaml, martini_L0-L2
# TREE_HASH is build/bench/tree-hash (or build-fixed/...), NAME double or fixed.
set -euo pipefail
mode=$1 tool=$2 name=$3
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
shared=${RTK_SHARED:-$root/../shared}
golden=$here/golden/tree-$name.sha256
cd "$root"
# Keys name corpus scenes corpus/<path under assets/trace> and the others by their
# path in the repository.
path_of() { case $1 in corpus/*) echo "$shared/cse457/assets/trace/${1#corpus/}" ;; *) echo "$1" ;; esac; }
key_of() { local p=${1#"$shared/cse457/assets/trace/"}; [ "$p" = "$1" ] && echo "$1" || echo "corpus/$p"; }
if [ "$mode" = bless ]; then
  keys=$( (cd "$shared/cse457/assets/trace" && find . -name '*.yaml' | sed 's|^\./|corpus/|') | sort)
  keys="$keys $(ls scenes/bench/*.yaml scenes/bench/scale/martini_L[012].yaml)"
else
  keys=$(awk '{print $2}' "$golden")
fi
paths=$(for k in $keys; do path_of "$k"; done)
one=$(mktemp) two=$(mktemp)
trap 'rm -f "$one" "$two"' EXIT
# shellcheck disable=SC2086
"$tool" --threads 1 --assets "$shared/cse457" $paths >"$one" 2>/dev/null || true
# shellcheck disable=SC2086
"$tool" --threads 2 --assets "$shared/cse457" $paths >"$two" 2>/dev/null || true
if [ "$mode" = bless ]; then
  cmp -s "$one" "$two" || { echo "tree-hash: not blessed: 1 and 2 threads built different trees" >&2; exit 1; }
  while read -r hash path; do printf '%s  %s\n' "$hash" "$(key_of "$path")"; done <"$one" >"$golden"
  echo "tree-hash: wrote $(wc -l <"$golden") hashes to $golden"
  exit 0
fi
fail=0 count=0
while read -r want key; do
  count=$((count + 1))
  path=$(path_of "$key")
  for got in "$one" "$two"; do
    hash=$(awk -v p="$path" '$2 == p {print $1}' "$got")
    if [ "$hash" != "$want" ]; then
      echo "tree-hash: $key ($([ "$got" = "$one" ] && echo 1 || echo 2) thread(s)): got ${hash:-no tree}, want $want" >&2
      fail=1
    fi
  done
done <"$golden"
echo "tree-hash-$name: $count scenes, $([ $fail = 0 ] && echo "all trees as pinned" || echo "MISMATCH")"
exit $fail
