#!/usr/bin/env bash
# The `make bench-scale` driver (run from the repository root after the binaries are
# built): the cost curve of rtk against Embree on the corpus martini glass at 0 to 5
# Loop levels (scenes/bench/scale/martini_L*.yaml, 12,891 to 13,188,108 triangles).
# For each size: the ray workload (BENCH_SIZE camera rays and their shadow rays), the
# BVH build on 1 and all threads, memory per triangle, primary and shadow rays one at a
# time and in packets on 1 and all threads (rtk double and Embree at its default
# quality), the ray-by-ray agreement, and `rtk render` of the scene with the default
# --max-memory. Prints a table, writes build/bench-scale/scale.csv and the log-log plot
# build/bench-scale/scale.png (gnuplot). Fails when a size's rays disagree with Embree
# on more than 0.01% or a render fails.
#
# Environment: BENCH_ASSETS (default ../shared/cse457), BENCH_SIZE (default 1024x1024),
# BENCH_ROUNDS (rtk and Embree take turns, default 2 rounds) and BENCH_REPEATS (each
# one's repeats in a round, default 3; each figure is the best of them all, as in
# bench/run.sh), BENCH_LEVELS (default "0 1 2 3 4 5").
set -eu

ASSETS=${BENCH_ASSETS:-../shared/cse457}
SIZE=${BENCH_SIZE:-1024x1024}
ROUNDS=${BENCH_ROUNDS:-2}
REPEATS=${BENCH_REPEATS:-3}
LEVELS=${BENCH_LEVELS:-0 1 2 3 4 5}
OUT=build/bench-scale
mkdir -p "$OUT"
rm -rf "$OUT"/*.txt "$OUT"/*.list "$OUT/scale.csv" "$OUT/scale.png" "$OUT/rounds"
mkdir -p "$OUT/rounds"

note() { printf '%s\n' "$*" >&2; }
val() { [ -f "$1" ] && awk -v k="$2" '$1 == k { print $2; exit }' "$1" || true; }
# Merges the rounds of kernel $1 into the file $2 (bench/best_of_rounds.awk).
best_of_rounds() {
    local files=() r
    for r in $(seq "$ROUNDS"); do files+=("$OUT/rounds/$1.$r.txt"); done
    awk -f bench/best_of_rounds.awk "${files[@]}" >"$2"
}

load_start=$(cut -d' ' -f1 /proc/loadavg)
csv=$OUT/scale.csv
echo "level,triangles,rtk_build_s,embree_build_s,rtk_build_all_s,embree_build_all_s,rtk_bytes_per_tri,embree_bytes_per_tri,rtk_primary_1,embree_primary_1,rtk_primary_all,embree_primary_all,rtk_shadow_1,embree_shadow_1,rtk_shadow_all,embree_shadow_all,rtk_primary_packets_1,embree_primary_packets_1,rtk_shadow_packets_1,embree_shadow_packets_1,primary_agree,shadow_agree,render_s,primary_agree_but_neighbours" >"$csv"
failed=0
for level in $LEVELS; do
    scene=scenes/bench/scale/martini_L$level.yaml
    D=$OUT/rtk-L$level.txt E=$OUT/embree-L$level.txt A=$OUT/agree-L$level.txt
    note "[level $level] workload"
    build/bench/rtk-bench rays "$scene" "$OUT/workload.bin" --assets "$ASSETS" --size "$SIZE" >"$OUT/rays-L$level.txt"
    for round in $(seq "$ROUNDS"); do
        embree_res="" rtk_res=""
        [ "$round" = 1 ] && embree_res=$OUT/embree.res rtk_res=$OUT/rtk.res
        # Embree first in odd rounds, rtk first in even ones.
        for turn in 1 2; do
            if [ $(((round + turn) % 2)) = 0 ]; then
                note "[level $level] Embree, round $round/$ROUNDS"
                build/bench/embree-harness "$OUT/workload.bin" --repeats "$REPEATS" --no-high \
                    ${embree_res:+--results "$embree_res"} >"$OUT/rounds/embree.$round.txt"
            else
                note "[level $level] rtk, round $round/$ROUNDS"
                build/bench/rtk-bench run "$scene" "$OUT/workload.bin" --assets "$ASSETS" --repeats "$REPEATS" \
                    ${rtk_res:+--results "$rtk_res"} >"$OUT/rounds/rtk.$round.txt"
            fi
        done
    done
    best_of_rounds embree "$E"
    best_of_rounds rtk "$D"
    # At 3 and 13 million triangles a pixel sees many triangle edges: camera rays that
    # the two kernels send to neighbouring triangles (sharing a vertex) are edge rounding,
    # counted apart (docs/performance.md, Method).
    if ! build/bench/rtk-bench agree "$OUT/workload.bin" "$OUT/rtk.res" "$OUT/embree.res" --neighbours >"$A" \
        2>"$OUT/agree-L$level.list"; then
        note "  rtk and Embree disagree on more than 0.01% of the rays (neighbouring triangles aside): $OUT/agree-L$level.list"
        failed=1
    fi
    rm -f "$OUT/workload.bin" "$OUT"/*.res
    note "[level $level] rtk render (default --max-memory)"
    start=$(date +%s.%N)
    if build/rtk render --quiet "$scene" --assets "$ASSETS" -o "$OUT/render.ppm" 2>"$OUT/render.err"; then
        render=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    else
        note "  render failed: $(head -n1 "$OUT/render.err")"
        render=failed
        failed=1
    fi
    rm -f "$OUT/render.ppm" "$OUT/render.err"
    row="$level,$(val "$D" triangles)"
    for k in build_s build_all_s bytes_per_tri primary_mrays_1 primary_mrays_all shadow_mrays_1 shadow_mrays_all \
        primary_packets_mrays_1 shadow_packets_mrays_1; do
        row="$row,$(val "$D" $k),$(val "$E" $k)"
    done
    echo "$row,$(val "$A" primary_agree),$(val "$A" shadow_agree),$render,$(val "$A" primary_agree_but_neighbours)" >>"$csv"
done

machine=$(bench/machine.sh)
printf 'rtk (kernel %s) vs Embree %s on %s, %s CPUs, %s; %s camera rays per size\n' "$(val "$D" kernel_name)" \
    "$(val "$E" kernel | sed 's/embree-//')" "$machine" "$(nproc)" "$(${CC:-cc} --version | head -n1)" "$SIZE"
printf 'load average: %s at start, %s at end\n\n' "$load_start" "$(cut -d' ' -f1 /proc/loadavg)"
awk -F, 'NR == 1 { next }
function r(a, b) { return a > 0 && b > 0 ? sprintf("%.2f", a / b) : "-" }
BEGIN { printf "%-5s %10s | %-21s %-21s | %-13s | %-21s %-21s | %-21s %-21s | %-21s %-21s | %-8s %-8s | %-8s | %s\n", "level", "triangles",
        "build 1 thr s (x)", "build all s (x)", "B/tri (x)", "primary 1 thr (x)", "primary all (x)", "shadow 1 thr (x)",
        "shadow all (x)", "prim. packets 1 (x)", "shad. packets 1 (x)", "agree %", "shadow %", "render s", "agree % but neighbouring triangles" }
{ printf "%-5s %10s | %6.3f %6.3f %5s   %6.3f %6.3f %5s   | %4.1f %4.1f %4s | %6.2f %6.2f %5s   %6.2f %6.2f %5s   | %6.2f %6.2f %5s   %6.2f %6.2f %5s   | %6.2f %6.2f %5s   %6.2f %6.2f %5s   | %8.4f %8.4f | %8s | %8.4f\n",
    $1, $2, $3, $4, r($3, $4), $5, $6, r($5, $6), $7, $8, r($7, $8), $9, $10, r($9, $10), $11, $12, r($11, $12),
    $13, $14, r($13, $14), $15, $16, r($15, $16), $17, $18, r($17, $18), $19, $20, r($19, $20), $21, $22, $23, $24 }' "$csv"
printf '\neach pair: rtk, Embree, and (x) = rtk/Embree; build in s (lower is better), rays in Mrays/s (higher is better).\n'

if command -v gnuplot >/dev/null; then
    gnuplot <<GNUPLOT
set terminal pngcairo size 1400,1000 font ",11"
set output "$OUT/scale.png"
set datafile separator ","
set key top left
set logscale xy
set grid
set xlabel "triangles"
set multiplot layout 2,2 title "rtk vs Embree on the martini glass at Loop levels 0-5 ($SIZE camera rays, load $load_start)"
set ylabel "BVH build, s"
plot "$csv" every ::1 using 2:3 with linespoints title "rtk, 1 thread", "" every ::1 using 2:4 with linespoints title "Embree, 1 thread", \
     "" every ::1 using 2:5 with linespoints title "rtk, all threads", "" every ::1 using 2:6 with linespoints title "Embree, all threads"
set ylabel "memory, bytes per triangle"
plot "$csv" every ::1 using 2:7 with linespoints title "rtk", "" every ::1 using 2:8 with linespoints title "Embree"
set ylabel "primary rays, Mrays/s"
plot "$csv" every ::1 using 2:9 with linespoints title "rtk, 1 thread", "" every ::1 using 2:10 with linespoints title "Embree, 1 thread", \
     "" every ::1 using 2:17 with linespoints title "rtk packets, 1 thread", "" every ::1 using 2:18 with linespoints title "Embree rtcIntersect8, 1 thread"
set ylabel "shadow rays, Mrays/s"
plot "$csv" every ::1 using 2:13 with linespoints title "rtk, 1 thread", "" every ::1 using 2:14 with linespoints title "Embree, 1 thread", \
     "" every ::1 using 2:19 with linespoints title "rtk packets, 1 thread", "" every ::1 using 2:20 with linespoints title "Embree rtcOccluded8, 1 thread"
unset multiplot
GNUPLOT
    note "wrote $csv and $OUT/scale.png"
else
    note "wrote $csv (no gnuplot: no plot)"
fi
if [ $failed != 0 ]; then
    echo "bench-scale: FAILED (see above)"
    exit 1
fi
