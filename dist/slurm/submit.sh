#!/usr/bin/env bash
# One frame as N parts on Slurm: an array job of the parts still to render, and a stitch
# job that runs when all of them have succeeded. Resumable: the array holds only the
# parts PARTS_DIR lacks or holds broken or from another render (rtk stitch --missing;
# those files are removed first), so a re-run after a cancelled or failed task renders
# just what is missing.
#   dist/slurm/submit.sh SCENE N PARTS_DIR OUT.png|OUT.ppm [rtk render options]
# Prints "array JOB parts LIST" (nothing when no part is missing) and "stitch JOB".
# Environment: RTK the rtk command (default rtk); SBATCH_PART / SBATCH_STITCH extra sbatch
# options (e.g. "--partition=render --cpus-per-task=8"); the usual SBATCH_* variables.
# PARTS_DIR must be on a file system every node sees; Slurm logs go there too.
set -euo pipefail
[ $# -ge 4 ] || {
  echo "usage: $0 SCENE N PARTS_DIR OUT [rtk render options]" >&2
  exit 2
}
scene=$(realpath "$1") n=$2 dir=$(realpath -m "$3") out=$(realpath -m "$4")
shift 4
here=$(cd "$(dirname "$0")" && pwd)
export RTK=${RTK:-rtk}
mkdir -p "$dir"
missing=$("$RTK" stitch --missing "$dir" "$scene" --tiles "$n" "$@")
for i in $missing; do rm -f "$dir/part-$i-of-$n.png"; done
# 0 1 2 5 7 8 -> 0-2,5,7-8: Slurm's array syntax, short for any N.
list=$(echo "$missing" | awk 'NF { if (NR > 1 && $1 == last + 1) { last = $1; next }
  if (NR > 1) printf "%s%s,", first, (last > first ? "-" last : ""); first = last = $1 }
  END { if (NR) printf "%s%s", first, (last > first ? "-" last : "") }')
dependency=()
if [ -n "$list" ]; then
  # shellcheck disable=SC2086
  array=$(sbatch --parsable --array="$list" --output="$dir/slurm-%A_%a.out" ${SBATCH_PART:-} \
    "$here/part.sbatch" "$scene" "$n" "$dir" "$@")
  array=${array%%;*}
  echo "array $array parts $list"
  dependency=(--dependency="afterok:$array" --kill-on-invalid-dep=yes)
fi
# shellcheck disable=SC2086
stitch=$(sbatch --parsable "${dependency[@]}" --output="$dir/slurm-stitch-%j.out" ${SBATCH_STITCH:-} \
  "$here/stitch.sbatch" "$n" "$dir" "$out")
echo "stitch ${stitch%%;*}"
