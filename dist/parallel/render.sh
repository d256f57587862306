#!/usr/bin/env bash
# One frame as N parts through GNU parallel, on this machine's cores or on the hosts of
# an --sshlogin list, then stitched. Resumable: a re-run renders only the parts that
# PARTS_DIR lacks or holds broken or from another render (rtk stitch --missing).
#   dist/parallel/render.sh SCENE N PARTS_DIR OUT.png|OUT.ppm [rtk render options]
# Environment: RTK the rtk command (default rtk); SSHLOGIN GNU parallel's --sshlogin
# list, e.g. "8/node1,8/node2" (default: this machine); JOBS parts at once per host
# (default: one per core); THREADS threads per part (default 1). Remote hosts need rtk
# at the same path and the scene, its assets and PARTS_DIR on a shared file system.
# The heart of it is one command line:
#   rtk stitch --missing DIR SCENE --tiles N | parallel -q rtk render SCENE --part {}/N -o DIR/part-{}-of-N.png
set -euo pipefail
[ $# -ge 4 ] || {
  echo "usage: $0 SCENE N PARTS_DIR OUT [rtk render options]" >&2
  exit 2
}
scene=$1 n=$2 dir=$3 out=$4
shift 4
rtk=${RTK:-rtk}
mkdir -p "$dir"
parts=()
for ((i = 0; i < n; i++)); do parts+=("$dir/part-$i-of-$n.png"); done
"$rtk" stitch --missing "$dir" "$scene" --tiles "$n" "$@" |
  parallel -q ${SSHLOGIN:+--sshlogin "$SSHLOGIN"} --jobs "${JOBS:-100%}" \
    "$rtk" render "$scene" --part "{}/$n" -o "$dir/part-{}-of-$n.png" --threads "${THREADS:-1}" --quiet "$@" &&
  "$rtk" stitch "${parts[@]}" -o "$out"
