#!/usr/bin/env bash
# Many frames (e.g. a turntable's scene files) as N parts each through one GNU parallel
# run, every part of every frame a job, then each frame stitched to OUT_DIR/NAME.png
# (NAME: the scene file's name without .yaml; its parts in OUT_DIR/NAME.parts/).
# Resumable as render.sh is: only missing, broken or stale parts are rendered again.
#   dist/parallel/frames.sh N OUT_DIR SCENE... [-- rtk render options]
# Environment: as render.sh (RTK, SSHLOGIN, JOBS, THREADS).
set -euo pipefail
[ $# -ge 3 ] || {
  echo "usage: $0 N OUT_DIR SCENE... [-- rtk render options]" >&2
  exit 2
}
n=$1 root=$2
shift 2
scenes=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do scenes+=("$1") && shift; done
[ $# -eq 0 ] || shift
rtk=${RTK:-rtk}
mkdir -p "$root"
# One line per part to render: scene, parts folder, index.
for scene in "${scenes[@]}"; do
  dir=$root/$(basename "$scene" .yaml).parts
  mkdir -p "$dir"
  "$rtk" stitch --missing "$dir" "$scene" --tiles "$n" "$@" | sed "s|^|$scene\t$dir\t|"
done |
  parallel -q --colsep '\t' ${SSHLOGIN:+--sshlogin "$SSHLOGIN"} --jobs "${JOBS:-100%}" \
    "$rtk" render "{1}" --part "{3}/$n" -o "{2}/part-{3}-of-$n.png" --threads "${THREADS:-1}" --quiet "$@"
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  parts=()
  for ((i = 0; i < n; i++)); do parts+=("$root/$name.parts/part-$i-of-$n.png"); done
  "$rtk" stitch "${parts[@]}" -o "$root/$name.png"
done
