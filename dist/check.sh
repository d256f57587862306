#!/usr/bin/env bash
# make check-dist: the recipes of dist/ on real engines. A corpus scene (meshes and a
# texture) and a Monte Carlo scene are rendered as parts through GNU parallel and through
# a one-node Slurm cluster started here (dist/slurm/local-cluster.sh), stitched, and the
# frame's SHA-256 (sha256sum of the PPM) must equal rtk render --hash of the whole frame.
# Then one part is killed while it renders (its rtk process under parallel, its array
# task by scancel under Slurm): the run must fail without a frame, and a re-run must
# render only the killed part and give the same hash. Every daemon and file it started
# is gone on every way out (trap). It never skips: a missing tool is an error.
#   dist/check.sh [RTK]    RTK defaults to build/rtk
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
rtk=$(realpath "${1:-$root/build/rtk}")
[ -x "$rtk" ] || { echo "check-dist: no rtk binary at $rtk" >&2; exit 2; }
corpus=${RTK_SHARED:-$root/../shared}/cse457/assets/trace
export RTK=$rtk

tmp=$(mktemp -d /tmp/rtk-check-dist.XXXXXX)
chmod 755 "$tmp" # munged wants every folder above its socket open to all
background="" daemons=""
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  [ -z "$background" ] || kill -- "-$background" 2>/dev/null || true
  "$here/slurm/local-cluster.sh" stop "$tmp/cluster" || rc=1
  rm -rf "$tmp"
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT TERM

say() { echo "check-dist: $*"; }
fail() {
  echo "check-dist: FAIL: $*" >&2
  exit 1
}
for tool in parallel munged slurmctld slurmd sbatch; do
  command -v "$tool" >/dev/null || fail "$tool is not installed (make check-dist installs slurm-wlm munge parallel)"
done

# The two scenes and their settings: small enough that the whole check takes minutes, and
# the Monte Carlo parts, which the kill tests stop mid-render, slow enough (about 2 s of
# one core each here) that a fast machine cannot finish one before the kill lands.
corpus_scene=$corpus/trimeshes/chess.yaml
corpus_opts=()
mc_scene=$corpus/more/cornell_ray.yaml
mc_opts=(--width 192 --height 192 --spp 64)
for scene in "$corpus_scene" "$mc_scene"; do
  [ -f "$scene" ] || fail "no $scene: the corpus is not under $corpus (set RTK_SHARED)"
done

whole_hash() { "$rtk" render "$1" --hash --quiet "${@:2}"; }
file_hash() { sha256sum "$1" | cut -d' ' -f1; }
# "inode name" of every part file in $1: a re-rendered part is a new file (atomic rename).
inodes() { (cd "$1" && stat -c '%i %n' part-*.png); }

# Asserts that frame $1 hashes as $2 (what: $3).
expect_hash() {
  [ -f "$1" ] || fail "$3: no frame at $1"
  local got
  got=$(file_hash "$1")
  [ "$got" = "$2" ] || fail "$3: stitched frame hashes $got, the whole frame $2"
  say "ok    $3: stitched == whole frame ($got)"
}

# Asserts that only part $3 of $2 in folder $1 was rendered again since inode list $4.
expect_only_rerendered() {
  local dir=$1 n=$2 k=$3 before=$4 after i
  after=$(inodes "$dir")
  for ((i = 0; i < n; i++)); do
    local was now
    was=$(grep " part-$i-of-$n.png\$" <<<"$before" || true)
    now=$(grep " part-$i-of-$n.png\$" <<<"$after" || true)
    [ -n "$now" ] || fail "part $i/$n missing after the re-run"
    if [ "$i" = "$k" ]; then
      [ -z "$was" ] || fail "part $k/$n was there before the re-run: the kill left it"
    else
      [ "$was" = "$now" ] || fail "part $i/$n was rendered again by the re-run (only part $k should be)"
    fi
  done
  say "ok    the re-run rendered part $k/$n only; the other $((n - 1)) parts are the same files"
}

# ---- GNU parallel ----

parallel_run() { # scene n dir out [render options]
  local start=$SECONDS
  "$here/parallel/render.sh" "$@" >"$tmp/parallel.log" 2>&1 || {
    cat "$tmp/parallel.log" >&2
    fail "dist/parallel/render.sh $* failed"
  }
  say "      parallel: $(basename "$1") in $2 parts: $((SECONDS - start)) s"
}

test_parallel() {
  local want_corpus=$1 want_mc=$2
  parallel_run "$corpus_scene" 3 "$tmp/p/chess" "$tmp/p/chess.ppm" "${corpus_opts[@]}"
  expect_hash "$tmp/p/chess.ppm" "$want_corpus" "parallel, chess, 3 parts"
  SSHLOGIN=2/: parallel_run "$corpus_scene" 2 "$tmp/p/chess-ssh" "$tmp/p/chess-ssh.ppm" "${corpus_opts[@]}"
  expect_hash "$tmp/p/chess-ssh.ppm" "$want_corpus" "parallel --sshlogin 2/:, chess, 2 parts"
  parallel_run "$mc_scene" 4 "$tmp/p/mc" "$tmp/p/mc.ppm" "${mc_opts[@]}"
  expect_hash "$tmp/p/mc.ppm" "$want_mc" "parallel, cornell_ray Monte Carlo, 4 parts"
  # A re-run over a complete folder renders nothing and stitches the same frame.
  local before
  before=$(inodes "$tmp/p/mc")
  rm "$tmp/p/mc.ppm"
  parallel_run "$mc_scene" 4 "$tmp/p/mc" "$tmp/p/mc.ppm" "${mc_opts[@]}"
  [ "$before" = "$(inodes "$tmp/p/mc")" ] || fail "a re-run over complete parts rendered some again"
  expect_hash "$tmp/p/mc.ppm" "$want_mc" "parallel re-run over complete parts (nothing rendered)"
}

# True when process $1 has its SIGTERM handler in place (bit 15 - 1 of SigCgt): rtk has
# started, so a signal now interrupts it rather than ending it before it can clean up.
catches_term() {
  local mask
  mask=$(awk '/^SigCgt:/ { print $2 }' "/proc/$1/status" 2>/dev/null) && [ -n "$mask" ] &&
    [ $((0x$mask >> 14 & 1)) = 1 ]
}

# Prints the pid of the rtk writing part $1 of $2 into folder $3, once it runs with its
# handler in place and 0.25 s more, past the scene's load (milliseconds) and into the
# render (about 2 s of one core here); fails after 120 s ($4 says under what).
rendering_pid() {
  local pattern pid start=$SECONDS
  pattern="^${rtk//./\\.} render .*-o ${3//./\\.}/part-$1-of-$2\\.png"
  until pid=$(pgrep -f -- "$pattern") && catches_term "$pid"; do
    [ $((SECONDS - start)) -lt 120 ] || fail "part $1/$2 never started under $4"
    sleep 0.02
  done
  sleep 0.25
  echo "$pid"
}

# Kills the rtk rendering part $k of $n into $dir once it runs; the run must fail with
# no frame, and a re-run must render part $k only.
test_parallel_kill() {
  local want=$1 n=4 k=1 dir=$tmp/p/kill out=$tmp/p/kill.ppm
  JOBS=2 setsid "$here/parallel/render.sh" "$mc_scene" $n "$dir" "$out" "${mc_opts[@]}" >"$tmp/kill.log" 2>&1 &
  background=$!
  local pid
  pid=$(rendering_pid $k $n "$dir" parallel)
  kill -TERM "$pid" 2>/dev/null || fail "part $k/$n finished before it could be killed: make the parts bigger"
  local rc=0
  wait "$background" || rc=$?
  background=""
  [ $rc != 0 ] || fail "parallel run with a killed part exited 0"
  [ ! -e "$out" ] || fail "parallel run with a killed part wrote a frame"
  [ ! -e "$dir/part-$k-of-$n.png" ] || fail "the killed part left a file"
  grep -q "interrupted; nothing written" "$tmp/kill.log" || fail "the killed rtk did not report its interruption"
  say "ok    parallel: part $k/$n killed while rendering; the run failed with no frame and no part $k"
  local before missing
  before=$(inodes "$dir")
  missing=$("$rtk" stitch --missing "$dir" "$mc_scene" --tiles $n "${mc_opts[@]}")
  [ "$missing" = "$k" ] || fail "rtk stitch --missing lists '$missing', expected $k"
  parallel_run "$mc_scene" $n "$dir" "$out" "${mc_opts[@]}"
  expect_only_rerendered "$dir" $n $k "$before"
  expect_hash "$out" "$want" "parallel re-run after the kill"
}

# ---- Slurm ----

job_states() { scontrol show job -o "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 | sort -u | xargs; }
all_done() {
  local states
  states=$(job_states "$1")
  [ -n "$states" ] && ! grep -qE 'PENDING|RUNNING|CONFIGURING|COMPLETING|SUSPENDED|REQUEUED|RESIZING' <<<"$states"
}
wait_done() { # job seconds
  local start=$SECONDS
  until all_done "$1"; do
    [ $((SECONDS - start)) -lt "$2" ] || fail "Slurm job $1 still '$(job_states "$1")' after $2 s"
    sleep 0.25
  done
}

# submit.sh's output: "array JOB parts LIST" (optional) and "stitch JOB".
submit() { # scene n dir out [options]
  "$here/slurm/submit.sh" "$@" >"$tmp/submit.log" 2>&1 || {
    cat "$tmp/submit.log" >&2
    fail "dist/slurm/submit.sh $* failed"
  }
  cat "$tmp/submit.log"
}
field() { awk -v k="$1" -v i="$2" '$1 == k { print $i }' <<<"$3"; }

slurm_run() { # what want scene n dir out [options]
  local what=$1 want=$2 start=$SECONDS
  shift 2
  local out=$4 sub stitch
  sub=$(submit "$@")
  stitch=$(field stitch 2 "$sub")
  wait_done "$stitch" 300
  [ "$(job_states "$stitch")" = COMPLETED ] || {
    cat "$3"/slurm-*.out >&2 2>/dev/null || true
    fail "$what: the stitch job ended $(job_states "$stitch")"
  }
  say "      slurm: $(basename "$1") in $2 parts: $((SECONDS - start)) s"
  expect_hash "$out" "$want" "$what"
}

test_slurm() {
  local want_corpus=$1 want_mc=$2
  "$here/slurm/local-cluster.sh" start "$tmp/cluster"
  export SLURM_CONF=$tmp/cluster/slurm.conf
  daemons=$(cat "$tmp"/cluster/slurmd.pid "$tmp"/cluster/slurmctld.pid "$tmp"/cluster/munge/munged.pid)
  slurm_run "slurm, chess, 3 parts" "$want_corpus" "$corpus_scene" 3 "$tmp/s/chess" "$tmp/s/chess.ppm" \
    "${corpus_opts[@]}"
  slurm_run "slurm, cornell_ray Monte Carlo, 4 parts" "$want_mc" "$mc_scene" 4 "$tmp/s/mc" "$tmp/s/mc.ppm" \
    "${mc_opts[@]}"
}

# Cancels array task $k while it runs: the array and the stitch job must end without a
# frame; a re-submission must queue part $k alone and stitch the same frame.
test_slurm_kill() {
  local want=$1 n=4 k=1 dir=$tmp/s/kill out=$tmp/s/kill.ppm
  local sub array stitch
  sub=$(submit "$mc_scene" $n "$dir" "$out" "${mc_opts[@]}")
  array=$(field array 2 "$sub")
  stitch=$(field stitch 2 "$sub")
  [ "$(field array 4 "$sub")" = "0-$((n - 1))" ] || fail "the first submission queued parts '$(field array 4 "$sub")'"
  rendering_pid $k $n "$dir" Slurm >/dev/null
  scancel "${array}_$k"
  wait_done "$array" 300
  wait_done "$stitch" 60
  local task_state
  task_state=$(job_states "${array}_$k")
  [ "$task_state" = CANCELLED ] || fail "array task ${array}_$k ended $task_state, not CANCELLED (finished too soon?)"
  [ "$(job_states "$stitch")" = CANCELLED ] || fail "the stitch job ended $(job_states "$stitch") after a cancelled part"
  [ ! -e "$out" ] || fail "a frame was written though a part was cancelled"
  [ ! -e "$dir/part-$k-of-$n.png" ] || fail "the cancelled task left its part"
  say "ok    slurm: task ${array}_$k cancelled while rendering; the stitch job was cancelled, no frame"
  local before again
  before=$(inodes "$dir")
  again=$(submit "$mc_scene" $n "$dir" "$out" "${mc_opts[@]}")
  [ "$(field array 4 "$again")" = "$k" ] || fail "the re-submission queued parts '$(field array 4 "$again")', not $k"
  wait_done "$(field stitch 2 "$again")" 300
  [ "$(job_states "$(field stitch 2 "$again")")" = COMPLETED ] || fail "the re-submission's stitch job failed"
  expect_only_rerendered "$dir" $n $k "$before"
  expect_hash "$out" "$want" "slurm re-submission after the cancel"
}

start=$SECONDS
say "$("$rtk" --version); GNU parallel $(parallel --version | head -1 | awk '{print $3}'); $(dpkg-query -W -f 'slurm-wlm ${Version}' slurm-wlm)"
want_corpus=$(whole_hash "$corpus_scene" "${corpus_opts[@]}")
want_mc=$(whole_hash "$mc_scene" "${mc_opts[@]}")
say "whole frames: chess $want_corpus, cornell_ray ${mc_opts[*]} $want_mc"
test_parallel "$want_corpus" "$want_mc"
test_parallel_kill "$want_mc"
test_slurm "$want_corpus" "$want_mc"
test_slurm_kill "$want_mc"
"$here/slurm/local-cluster.sh" stop "$tmp/cluster"
for pid in $daemons; do
  ! kill -0 "$pid" 2>/dev/null || fail "daemon $pid ($(cat "/proc/$pid/comm" 2>/dev/null)) still runs after stop"
done
say "ok    the daemons (${daemons//$'\n'/ }) stopped"
say "passed in $((SECONDS - start)) s"
