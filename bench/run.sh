#!/usr/bin/env bash
# The `make bench` driver (run from the repository root after the binaries are built):
# makes the ray workload once, runs rtk double, rtk fixed and Embree on it, checks ray
# by ray that rtk and Embree answer alike, times the render of every corpus and
# benchmark scene, then prints one table and writes build/bench/results.csv and
# build/bench/results.json. Progress goes to stderr. Fails (exit 1, after the table,
# listing the rays) when rtk and Embree agree on fewer than 99.99% of the camera rays'
# triangles or of the shadow rays' verdicts.
#
# Environment: BENCH_FIXED=1 when build-fixed/ is usable; BENCH_ASSETS (default
# ../shared/cse457, the folder holding assets/); BENCH_MESH (the scene whose triangles
# and camera make the rays, default scenes/bench/dense_mesh.yaml; triangles only);
# BENCH_SIZE (camera rays, default 1024x1024); BENCH_ROUNDS (the kernels take turns,
# default 3 rounds) and BENCH_REPEATS (each kernel's repeats in a round, default 3):
# each row is the best of them all; BENCH_RENDER_REPEATS (each render's runs, default 3;
# its row is the best).
set -eu

ASSETS=${BENCH_ASSETS:-../shared/cse457}
FIXED=${BENCH_FIXED:-0}
SIZE=${BENCH_SIZE:-1024x1024}
ROUNDS=${BENCH_ROUNDS:-3}
REPEATS=${BENCH_REPEATS:-3}
RENDER_REPEATS=${BENCH_RENDER_REPEATS:-3}
OUT=build/bench
MESH=${BENCH_MESH:-scenes/bench/dense_mesh.yaml}
ROWS=$OUT/rows.tsv
mkdir -p "$OUT"
# A kernel not run this time must not report old figures.
rm -rf "$OUT"/rtk-*.txt "$OUT/embree.txt" "$OUT"/agree-* "$OUT/rounds"
mkdir -p "$OUT/rounds"

note() { printf '%s\n' "$*" >&2; }
# The value of `key` in a harness's "key value" output file, or empty.
val() { [ -f "$1" ] && awk -v k="$2" '$1 == k { print $2; exit }' "$1" || true; }

if [ ! -d "$ASSETS/assets" ]; then
    note "bench: no assets/ folder in $ASSETS (set BENCH_ASSETS to the folder that contains assets/)"
    exit 3
fi
for knob in ROUNDS REPEATS RENDER_REPEATS; do
    if ! [[ ${!knob} =~ ^[1-9][0-9]*$ ]]; then
        note "bench: BENCH_$knob must be a whole number of 1 or more, not '${!knob}'"
        exit 3
    fi
done
if [ ! -f "$MESH" ]; then
    note "bench: no scene $MESH (BENCH_MESH names a scene file whose triangles and camera make the rays)"
    exit 3
fi

# Corpus scenes that render deterministically and have all their files.
corpus=()
skipped=()
for scene in "$ASSETS"/assets/trace/*/*.yaml; do
    name=${scene#"$ASSETS"/assets/trace/}
    if tr -d '\r' <"$scene" | grep -Eq '^ *Monte Carlo: *[1-9]'; then
        skipped+=("$name (Monte Carlo)")
        continue
    fi
    missing=$(tr -d '\r' <"$scene" | sed -n 's/^ *Path: *//p' | while read -r p; do
        [ -e "$ASSETS/$p" ] || printf '%s ' "$p"; done)
    if [ -n "$missing" ]; then
        skipped+=("$name (missing ${missing% })")
        continue
    fi
    corpus+=("$scene")
done
bench_scenes=(scenes/bench/dense_mesh.yaml scenes/bench/spheres.yaml scenes/bench/deep.yaml)
case " ${bench_scenes[*]} " in *" $MESH "*) ;; *) bench_scenes+=("$MESH") ;; esac
kernels=(double)
[ "$FIXED" = 1 ] && kernels+=(fixed)
steps=$((2 + ROUNDS * (1 + ${#kernels[@]}) + ${#kernels[@]} * (${#corpus[@]} + ${#bench_scenes[@]})))
step=0
progress() { step=$((step + 1)); note "[$step/$steps] $*"; }

load=$(cut -d' ' -f1 /proc/loadavg)
cpus=$(nproc)
if awk -v l="$load" -v c="$cpus" 'BEGIN { exit !(l > 0.5 * c) }'; then
    note "bench: warning: load average $load on $cpus CPUs before starting; timings will be noisy"
fi

progress "workload: $MESH, $SIZE camera rays and their shadow rays"
build/bench/rtk-bench rays "$MESH" "$OUT/workload.bin" --assets "$ASSETS" --size "$SIZE" >"$OUT/rays.txt"
# The kernels take turns, round after round, in the opposite order every other round:
# this VM's speed drifts over minutes, and a drift then reaches every kernel alike
# instead of favouring the one that ran in a fast spell. Each row keeps its best
# (bench/best_of_rounds.awk); the answers are written in the first round. Within a
# round each measurement repeats: Embree's first two builds on a fresh device are the
# slow ones, so three repeats reach its usual speed.
run_kernel() { # KERNEL ROUND
    local res="" dir=build
    [ "$2" = 1 ] && res=$OUT/$1.res
    progress "$1, round $2/$ROUNDS"
    case $1 in
    embree)
        build/bench/embree-harness "$OUT/workload.bin" --repeats "$REPEATS" ${res:+--results "$res"} \
            >"$OUT/rounds/$1.$2.txt"
        ;;
    *)
        [ "$1" = rtk-fixed ] && dir=build-fixed
        "$dir/bench/rtk-bench" run "$MESH" "$OUT/workload.bin" --assets "$ASSETS" --repeats "$REPEATS" \
            ${res:+--results "$res"} >"$OUT/rounds/$1.$2.txt"
        ;;
    esac
}
# Merges the rounds of kernel $1 into the file $2 (bench/best_of_rounds.awk).
best_of_rounds() {
    local files=() r
    for r in $(seq "$ROUNDS"); do files+=("$OUT/rounds/$1.$r.txt"); done
    awk -f bench/best_of_rounds.awk "${files[@]}" >"$2"
}
turns=(embree)
for k in "${kernels[@]}"; do turns+=("rtk-$k"); done
for round in $(seq "$ROUNDS"); do
    if [ $((round % 2)) = 1 ]; then
        for kernel in "${turns[@]}"; do run_kernel "$kernel" "$round"; done
    else
        for ((i = ${#turns[@]} - 1; i >= 0; i--)); do run_kernel "${turns[i]}" "$round"; done
    fi
done
for kernel in "${turns[@]}"; do best_of_rounds "$kernel" "$OUT/$kernel.txt"; done
# Ray by ray: rtk and Embree must agree on the triangle hit (or the miss) of 99.99% of
# the camera rays and on 99.99% of the shadow rays; the rays that differ are listed.
agreement=ok
for k in "${kernels[@]}"; do
    if ! build/bench/rtk-bench agree "$OUT/workload.bin" "$OUT/rtk-$k.res" "$OUT/embree.res" \
        >"$OUT/agree-$k.txt" 2>"$OUT/agree-$k.list"; then
        agreement=failed
    fi
done
rm -f "$OUT/workload.bin" "$OUT"/*.res

D=$OUT/rtk-double.txt F=$OUT/rtk-fixed.txt E=$OUT/embree.txt
: >"$ROWS"
# row METRIC UNIT DOUBLE FIXED EMBREE (empty = not measured)
row() { printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" "$5" >>"$ROWS"; }
# Field `col` of the row named `metric` written so far.
val_row() { awk -F '\t' -v m="$1" -v c="$2" '$1 == m { print $c; exit }' "$ROWS"; }
# a / b to two decimals, or "" unless both are positive numbers.
speedup() { awk -v a="$1" -v b="$2" 'BEGIN { if (a ~ /^[0-9.]+$/ && b ~ /^[0-9.]+$/ && b > 0) printf "%.2f", a / b }'; }
row "BVH build vs Embree 1 thread" s "$(val $D build_s)" "$(val $F build_s)" "$(val $E build_s)"
row "BVH build vs Embree 1 thread, CPU time" s "$(val $D build_cpu_s)" "$(val $F build_cpu_s)" "$(val $E build_cpu_s)"
row "BVH build vs Embree all threads" s "$(val $D build_all_s)" "$(val $F build_all_s)" "$(val $E build_all_s)"
row "BVH build speed-up $cpus/1 threads" x "$(speedup "$(val $D build_s)" "$(val $D build_all_s)")" \
    "$(speedup "$(val $F build_s)" "$(val $F build_all_s)")" "$(speedup "$(val $E build_s)" "$(val $E build_all_s)")"
row "BVH build vs Embree HIGH quality, 1 thread" s "$(val $D build_s)" "$(val $F build_s)" "$(val $E build_high_s)"
row "BVH build vs Embree HIGH quality, all threads" s "$(val $D build_all_s)" "$(val $F build_all_s)" \
    "$(val $E build_high_all_s)"
row "SAH cost of the tree (node visit = triangle test = 1)" count "$(val $D sah_cost)" "$(val $F sah_cost)" ""
for q in primary shadow; do
    row "$q rays, 1 thread" Mrays/s "$(val $D ${q}_mrays_1)" "$(val $F ${q}_mrays_1)" "$(val $E ${q}_mrays_1)"
    row "$q rays, 1 thread, CPU time" Mrays/s "$(val $D ${q}_mrays_1_cpu)" "$(val $F ${q}_mrays_1_cpu)" \
        "$(val $E ${q}_mrays_1_cpu)"
    row "$q rays, $cpus threads" Mrays/s "$(val $D ${q}_mrays_all)" "$(val $F ${q}_mrays_all)" "$(val $E ${q}_mrays_all)"
    row "$q speed-up $cpus/1 threads" x "$(speedup "$(val $D ${q}_mrays_all)" "$(val $D ${q}_mrays_1)")" \
        "$(speedup "$(val $F ${q}_mrays_all)" "$(val $F ${q}_mrays_1)")" \
        "$(speedup "$(val $E ${q}_mrays_all)" "$(val $E ${q}_mrays_1)")"
    row "$q rays vs Embree's HIGH tree, 1 thread" Mrays/s "$(val $D ${q}_mrays_1)" "$(val $F ${q}_mrays_1)" \
        "$(val $E ${q}_high_mrays_1)"
    row "$q rays vs Embree's HIGH tree, $cpus threads" Mrays/s "$(val $D ${q}_mrays_all)" "$(val $F ${q}_mrays_all)" \
        "$(val $E ${q}_high_mrays_all)"
    api=rtcIntersect8; [ $q = shadow ] && api=rtcOccluded8
    row "$q packets (4x2 px; Embree $api), 1 thread" Mrays/s \
        "$(val $D ${q}_packets_mrays_1)" "$(val $F ${q}_packets_mrays_1)" "$(val $E ${q}_packets_mrays_1)"
    row "$q packets, 1 thread, CPU time" Mrays/s "$(val $D ${q}_packets_mrays_1_cpu)" \
        "$(val $F ${q}_packets_mrays_1_cpu)" "$(val $E ${q}_packets_mrays_1_cpu)"
    row "$q packets, $cpus threads" Mrays/s "$(val $D ${q}_packets_mrays_all)" "$(val $F ${q}_packets_mrays_all)" \
        "$(val $E ${q}_packets_mrays_all)"
    row "$q hits" count "$(val $D ${q}_hits)" "$(val $F ${q}_hits)" "$(val $E ${q}_hits)"
    row "$q rays agreeing with Embree ray by ray" % "$(val "$OUT/agree-double.txt" ${q}_agree)" \
        "$(val "$OUT/agree-fixed.txt" ${q}_agree)" ""
done
row "BVH + mesh memory" B/tri "$(val $D bytes_per_tri)" "$(val $F bytes_per_tri)" "$(val $E bytes_per_tri)"
row "BVH + mesh memory vs Embree HIGH" B/tri "$(val $D bytes_per_tri)" "$(val $F bytes_per_tri)" \
    "$(val $E bytes_per_tri_high)"

# Sets t to the best of RENDER_REPEATS wall times of `rtk render --quiet` (load, build,
# render, write a PPM) for one kernel, or "failed", or "" when that kernel is not built.
# Extra arguments go to rtk render.
render_time() {
    local k=$1 scene=$2 dir=build start run one
    shift 2
    t=""
    [ "$k" = fixed ] && dir=build-fixed
    if [ "$k" = fixed ] && [ "$FIXED" != 1 ]; then return; fi
    progress "render ${scene#"$ASSETS"/assets/trace/} ($k${1:+ $*})"
    for run in $(seq "$RENDER_REPEATS"); do
        start=$(date +%s.%N)
        if ! "$dir/rtk" render --quiet "$scene" --assets "$ASSETS" -o "$OUT/render.ppm" "$@" 2>"$OUT/render.err"; then
            note "  failed: $(head -n1 "$OUT/render.err")"
            t=failed
            return
        fi
        one=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
        if [ "$run" = 1 ] || awk -v a="$one" -v b="$t" 'BEGIN { exit !(a < b) }'; then t=$one; fi
    done
}
for scene in "${corpus[@]}" "${bench_scenes[@]}"; do
    render_time double "$scene"
    dt=$t
    render_time fixed "$scene"
    row "render ${scene#"$ASSETS"/assets/trace/}" s "$dt" "$t" ""
done
# Thread scaling of a whole render (double only, to keep `make bench` short): the deep
# scene spends nearly all its time tracing.
deep=scenes/bench/deep.yaml
render_time double $deep --threads 1
row "render $deep, 1 thread" s "$t" "" ""
row "render $deep speed-up $cpus/1 threads" x "$(speedup "$t" "$(val_row "render $deep" 3)")" "" ""
rm -f "$OUT/render.ppm" "$OUT/render.err"

machine=$(bench/machine.sh)
compiler=$(${CC:-cc} --version | head -n1)
embree=$(val $E kernel)
header="rtk vs Embree ${embree#embree-} on $machine, $cpus CPUs, Linux $(uname -r), $compiler;"
header="$header rtk kernel $(val $D kernel_name); mesh $MESH: $(val $D triangles) triangles,"
header="$header $(val "$OUT/rays.txt" primary_rays) camera rays ($SIZE), $(val "$OUT/rays.txt" shadow_rays) shadow rays"
[ "$FIXED" = 1 ] || header="$header; fixed: not built"
load="$load at start, $(cut -d' ' -f1 /proc/loadavg) at end"
awk -v header="$header" -v fixed="$FIXED" -v csv="$OUT/results.csv" -v json="$OUT/results.json" \
    -v skipped="$(printf '%s; ' "${skipped[@]}")" -v load="$load" -f bench/report.awk "$ROWS"
note "wrote $OUT/results.csv and $OUT/results.json"
if [ "$agreement" != ok ]; then
    for k in "${kernels[@]}"; do
        echo "rtk $k against Embree, the rays that differ (rtk / Embree):"
        cat "$OUT/agree-$k.list"
    done
    echo "bench: FAILED: rtk and Embree agree on fewer than 99.99% of the rays (see above)"
    exit 1
fi
