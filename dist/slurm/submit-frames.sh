#!/usr/bin/env bash
# Many frames (e.g. a turntable's scene files) on Slurm: submit.sh for each, so one
# array job of parts and one stitch job per frame, all queued at once. Frame NAME (the
# scene file's name without .yaml) goes to OUT_DIR/NAME.png, its parts to
# OUT_DIR/NAME.parts/. Resumable as submit.sh is.
#   dist/slurm/submit-frames.sh N OUT_DIR SCENE... [-- rtk render options]
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
here=$(cd "$(dirname "$0")" && pwd)
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  echo "frame $name"
  "$here/submit.sh" "$scene" "$n" "$root/$name.parts" "$root/$name.png" "$@"
done
