#!/usr/bin/env bash
# The figures of docs/distributed.md: per-part overhead, wall time for 1, 2, 4, 8 parts
# through GNU parallel and a one-node Slurm, the cost of stitching, and how even the
# cut's parts are. Prints a report; passes or fails nothing (timings are no test).
#   dist/bench.sh [RTK [SECTION...]]    RTK defaults to build/rtk; run as root (Slurm)
# Sections: overhead balance scaling latency stitch (default: all).
# Wall times on a shared machine are noisy: the load average is printed with them, and
# CPU times (user + sys, less sensitive to other work) next to them where rtk's own
# processes can be measured.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
rtk=$(realpath "${1:-$root/build/rtk}")
[ $# -le 1 ] || shift
sections=" ${*:-overhead balance scaling latency stitch} "
want() { [[ $sections == *" $1 "* ]]; }
shared=${RTK_SHARED:-$root/../shared}
export RTK=$rtk
tmp=$(mktemp -d /tmp/rtk-bench-dist.XXXXXX)
chmod 755 "$tmp"
cleanup() {
  "$here/slurm/local-cluster.sh" stop "$tmp/cluster" || true
  rm -rf "$tmp"
}
trap cleanup EXIT

deep=$root/scenes/bench/deep.yaml
deep_opts=(--spp 4)
mesh=$root/scenes/bench/dense_mesh.yaml
mesh_opts=(--assets "$shared/cse457")
load() { cut -d' ' -f1-3 /proc/loadavg; }
# "wall cpu" seconds of a command (cpu: user + sys of it and its children).
timed() {
  /usr/bin/time -f '%e %U %S' -o "$tmp/time" "$@" >/dev/null
  awk '{ printf "%.2f %.2f", $1, $2 + $3 }' "$tmp/time"
}
# The smallest of three runs' "wall cpu", by cpu.
best_of_3() {
  for _ in 1 2 3; do
    timed "$@"
    echo
  done | sort -n -k2 | head -1
}

echo "rtk: $("$rtk" --version); $(nproc) cores; load average at start $(load)"

cluster_up() {
  [ -e "$tmp/cluster/slurm.conf" ] || "$here/slurm/local-cluster.sh" start "$tmp/cluster" >/dev/null
  export SLURM_CONF=$tmp/cluster/slurm.conf
}
# Wall seconds of a Slurm submission of scene in n parts until its frame is written.
slurm_wall() { # scene n [options]
  local scene=$1 n=$2 start stitch
  shift 2
  rm -rf "$tmp/s" "$tmp/s.png"
  start=$(date +%s.%N)
  stitch=$("$here/slurm/submit.sh" "$scene" "$n" "$tmp/s" "$tmp/s.png" "$@" | awk '$1 == "stitch" { print $2 }')
  until [ -e "$tmp/s.png" ] || scontrol show job -o "$stitch" | grep -qE 'JobState=(FAILED|CANCELLED)'; do sleep 0.1; done
  [ -e "$tmp/s.png" ] || { echo "slurm: the stitch job failed" >&2; exit 1; }
  echo "$(date +%s.%N) - $start" | bc | xargs printf '%.2f'
}

want overhead && echo && echo "== per-part overhead, seconds (wall cpu), best of 3, 1 thread"
want overhead && for s in deep mesh; do
  if [ $s = deep ]; then scene=$deep opts=("${deep_opts[@]}"); else scene=$mesh opts=("${mesh_opts[@]}"); fi
  mkdir -p "$tmp/empty"
  echo "$(basename "$scene"): load+build+digests+1 pixel: $(best_of_3 "$rtk" render "$scene" "${opts[@]}" \
    --region 0,0,1,1 -o "$tmp/px.png" --threads 1)"
  echo "$(basename "$scene"): load+build+digests+cut (stitch --missing, 8 parts): $(best_of_3 "$rtk" stitch \
    --missing "$tmp/empty" "$scene" "${opts[@]}" --tiles 8 --threads 1)"
  echo "$(basename "$scene"): whole 512x512 frame at 1 sample, 1 thread: $(best_of_3 "$rtk" render "$scene" \
    "${opts[@]}" --spp 1 --hash --threads 1)"
done

want balance && echo && echo "== balance: deep.yaml ${deep_opts[*]}, 8 parts, cpu seconds of each part (1 thread)"
want balance && for cut in part equal; do
  line=""
  for i in 0 1 2 3 4 5 6 7; do
    if [ $cut = part ]; then where=(--part "$i/8"); else where=(--region "0,$((64 * i)),512,$((64 * i + 64))"); fi
    line="$line $(timed "$rtk" render "$deep" "${deep_opts[@]}" "${where[@]}" -o "$tmp/b.png" --threads 1 | cut -d' ' -f2)"
  done
  echo "$cut:$line" | awk '{ max = 0; sum = 0; for (i = 2; i <= NF; i++) { sum += $i; if ($i > max) max = $i }
    printf "%-6s %s  max/mean %.2f\n", $1, substr($0, length($1) + 2), max / (sum / (NF - 1)) }'
done

if want scaling; then
echo
echo "== deep.yaml ${deep_opts[*]} 512x512: whole frame and N parts, seconds"
echo "whole frame, 2 threads (wall cpu): $(timed "$rtk" render "$deep" "${deep_opts[@]}" --hash --threads 2)  load $(load)"
for n in 1 2 4 8; do
  rm -rf "$tmp/p"
  echo "parallel, $n parts, 2 jobs x 1 thread (wall cpu): $(JOBS=2 timed "$here/parallel/render.sh" "$deep" "$n" \
    "$tmp/p" "$tmp/p.png" "${deep_opts[@]}")  load $(load)"
done
cluster_up
for n in 1 2 4 8; do
  echo "slurm, $n parts, 1 cpu per task (wall): $(slurm_wall "$deep" "$n" "${deep_opts[@]}")  load $(load)"
done
fi

chess=$shared/cse457/assets/trace/trimeshes/chess.yaml
if want latency; then
  echo
  echo "== recipe latency: chess.yaml at 16x16 (next to no rendering), wall seconds"
  for n in 1 8; do
    rm -rf "$tmp/l"
    echo "parallel, $n parts: $(JOBS=2 timed "$here/parallel/render.sh" "$chess" "$n" "$tmp/l" "$tmp/l.png" --width 16 \
      --height 16 | cut -d' ' -f1)  load $(load)"
  done
  cluster_up
  for n in 1 8; do
    echo "slurm, $n parts: $(slurm_wall "$chess" "$n" --width 16 --height 16)  load $(load)"
  done
fi

if want stitch; then
  echo
  echo "== stitch of a 2048x2048 frame in 4 parts, seconds (wall cpu), best of 3"
  cornell=$shared/cse457/assets/trace/more/cornell_ray.yaml
  for what in chess cornell; do
    if [ $what = chess ]; then scene=$chess opts=(); else scene=$cornell opts=(--spp 1 --depth 1); fi
    rm -rf "$tmp/c"
    JOBS=2 "$here/parallel/render.sh" "$scene" 4 "$tmp/c" "$tmp/c.ppm" --width 2048 --height 2048 "${opts[@]}"
    parts=("$tmp"/c/part-{0,1,2,3}-of-4.png)
    echo "$what ${opts[*]}: parts $(du -cb "${parts[@]}" | tail -1 | cut -f1) bytes"
    echo "  stitch to PNG: $(best_of_3 "$rtk" stitch "${parts[@]}" -o "$tmp/c2.png")"
    echo "  stitch to PPM: $(best_of_3 "$rtk" stitch "${parts[@]}" -o "$tmp/c2.ppm")"
    echo "  stitch --check of the 4 parts: $(best_of_3 "$rtk" stitch --check "${parts[@]}")"
  done
fi
echo
echo "load average at the end $(load)"
