#!/usr/bin/env bash
# The determinism matrix: every build of the kernel must render every golden scene to
# the bytes pinned in tests/golden/matrix-<real>.sha256 (SIZE x SIZE renders, 64 by
# default; make check pins full size in tests/golden/<real>.sha256). For each scalar
# type given (double, fixed), each cell below is compared with the pinned hashes, so a
# change that moves every target together fails too:
#   1. the host rtk at its default settings, with other thread counts and tiles, with
#      --no-bvh (every primitive tested), and with each BVH kernel this CPU runs
#      (--kernel portable, sse2, avx2, avx512: one ray at a time, packets in 128- and
#      256-bit vectors, a packet's triangle tests in 512-bit ones);
#   2. the core alone (targets/hash_driver.c reading `rtk pack` blobs), built with gcc
#      and clang at -O0/-O1/-O2/-O3/-Os, for i686 (-m32 -msse2 -mfpmath=sse), and
#      cross-compiled for aarch64, riscv64 and big-endian s390x (run under qemu-user);
#      the -O2 x86 drivers once with each kernel the CPU runs, the others with their
#      build's default. The i686 driver runs natively where the kernel executes 32-bit
#      binaries, else under qemu-i386 (some kernels are built without 32-bit support:
#      "Exec format error").
# Cells run two at a time (JOBS=N to change). Prints one line per cell, saying how its
# driver ran, and "determinism: N passed, M failed".
#   targets/determinism.sh [double] [fixed]          check
#   targets/determinism.sh --bless [double] [fixed]  re-pin from the host rtk (make bless)
set -euo pipefail
cd "$(dirname "$0")/.."
bless=0
if [ "${1:-}" = --bless ]; then bless=1; shift; fi
reals=${*:-double fixed}
size=64 # the pinned size
jobs=${JOBS:-2}
corpus=${RTK_SHARED:-../shared}/cse457/assets/trace
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

scenes=()
while read -r scene _; do
  case $scene in ''|'#'*) continue ;; esac
  scenes+=("$scene")
done <tests/golden/scenes.txt
path_of() { local s=$1; case $s in corpus/*) echo "$corpus/${s#corpus/}" ;; *) echo "$s" ;; esac; }
pinned_file() { echo "tests/golden/matrix-$1.sha256"; }
blob_of() { echo "$work/$1.$(echo "$2" | tr / _).rtscene"; }

if [ $bless = 1 ]; then
  for real in $reals; do
    build=build; [ "$real" = fixed ] && build=build-fixed
    make -s RT_REAL="$real" "$build/rtk" >/dev/null
    out=$(pinned_file "$real")
    for s in "${scenes[@]}"; do
      echo "$("$build/rtk" render "$(path_of "$s")" --width "$size" --height "$size" --hash --quiet)  $s"
    done >"$out.tmp"
    mv "$out.tmp" "$out"
    echo "determinism: wrote ${#scenes[@]} ${size}x${size} hashes to $out"
  done
  exit 0
fi

need() { # installs Debian packages whose command or file is missing
  local missing=()
  while [ $# -gt 0 ]; do [ -e "$1" ] || command -v "$1" >/dev/null 2>&1 || missing+=("$2"); shift 2; done
  [ ${#missing[@]} = 0 ] && return
  local sudo=; [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}
need clang clang aarch64-linux-gnu-gcc gcc-aarch64-linux-gnu qemu-aarch64 qemu-user qemu-i386 qemu-user \
     riscv64-linux-gnu-gcc gcc-riscv64-linux-gnu qemu-riscv64 qemu-user \
     s390x-linux-gnu-gcc gcc-s390x-linux-gnu qemu-s390x qemu-user \
     /usr/lib32/libc.a libc6-dev-i386 /usr/lib/gcc/x86_64-linux-gnu/12/32/libgcc.a lib32gcc-12-dev

# Probed once: can this kernel execute a static i686 binary itself?
printf 'int main(void) { return 0; }\n' >"$work/probe.c"
gcc -m32 -static "$work/probe.c" -o "$work/probe-i686"
if "$work/probe-i686" 2>/dev/null; then i686_run=env; else i686_run=qemu-i386; fi
echo "i686 binaries run $([ "$i686_run" = env ] && echo natively || echo 'under qemu-i386 (the kernel cannot execute them)')"

# Cell N writes "ok LABEL" or "DIFFERS LABEL" and the first differing lines to
# $work/result/N (scratch in $work/tmp/N.*); the summary reads them in order.
mkdir -p "$work/result" "$work/tmp"
cells=0
verdict() { # verdict LABEL PINNED OUT RESULT
  if cmp -s "$2" "$3"; then echo "ok      $1" >"$4"
  else { echo "DIFFERS $1 (from $2)"; diff "$2" "$3" | grep '^>' | head -5 || true; } >"$4"; fi
}
host_cell() { # host_cell REAL RTK PINNED N OPTS...
  local real=$1 rtk=$2 pinned=$3 result=$work/result/$4 out=$work/tmp/$4.out
  shift 4
  for s in "${scenes[@]}"; do
    echo "$("$rtk" render "$(path_of "$s")" --width "$size" --height "$size" --hash --quiet "$@")  $s"
  done >"$out"
  verdict "rtk ${*:-(default threads and tiles)}" "$pinned" "$out" "$result"
}
core_cell() { # core_cell REAL PINNED N NAME CC OPT EXTRA RUN KERNELS
  local real=$1 pinned=$2 result=$work/result/$3 tmp=$work/tmp/$3 name=$4 cc=$5 opt=$6 extra=${7//_/ } run=$8 kernels=$9
  [ "$run" = i686 ] && run=$i686_run
  local exe=$work/driver-$real-$name flags="-std=c11 -ffp-contract=off -fno-math-errno -Iinclude -Icore"
  [ "$real" = fixed ] && flags="$flags -DRT_REAL_FIXED"
  # shellcheck disable=SC2086
  if ! $cc $flags $opt $extra targets/hash_driver.c $(make -s core-sources RT_REAL="$real") -o "$exe" 2>"$tmp.err"; then
    { echo "DIFFERS core $name (does not build)"; head -5 "$tmp.err"; } >"$result"
    return
  fi
  : >"$result"
  local k how
  how=$([ "$run" = env ] && echo native || echo "$run")
  for k in ${kernels//,/ }; do
    for s in "${scenes[@]}"; do
      # shellcheck disable=SC2086
      echo "$($run "$exe" "$(blob_of "$real" "$s")" 512 ${k#default})  $s"
    done >"$tmp.out"
    verdict "core $name, ${k} kernel ($how)" "$pinned" "$tmp.out" "$tmp.one"
    cat "$tmp.one" >>"$result"
  done
}
launch() { # runs a cell in the background, at most $jobs at once
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  "$@" &
}

for real in $reals; do
  build=build; [ "$real" = fixed ] && build=build-fixed
  make -s RT_REAL="$real" "$build/rtk" >/dev/null
  rtk=$build/rtk
  pinned=$(pinned_file "$real")
  [ -f "$pinned" ] || { echo "determinism: no pinned hashes in $pinned (make bless)" >&2; exit 1; }
  for s in "${scenes[@]}"; do "$rtk" pack "$(path_of "$s")" --width "$size" --height "$size" -o "$(blob_of "$real" "$s")"; done
  # The kernels the host runs (the fixed build has only the portable one).
  kernels=()
  for k in portable sse2 avx2 avx512; do
    if "$rtk" render scenes/demo.yaml --width 4 --height 4 --hash --quiet --kernel $k >/dev/null 2>&1; then
      kernels+=("$k")
    else
      echo "$real: no cells for the $k kernel: this CPU or build does not run it"
    fi
  done
  native_kernels=$(IFS=,; echo "${kernels[*]}")
  # qemu runs no AVX2 or AVX-512 here: a qemu-run x86 driver tries the others.
  emulated_kernels=$(IFS=,; echo "${kernels[*]}" | sed 's/avx[0-9]*//g; s/,,*/,/g; s/,$//')
  # --no-bvh tests every primitive (64x64: brute force at full size takes minutes per mesh scene).
  mine=()
  opt_sets=("" "--threads 1" "--threads 2 --tile 16" "--threads 7 --tile 5" "--threads 3 --tile 64" "--no-bvh")
  for k in "${kernels[@]}"; do opt_sets+=("--kernel $k"); done
  for opts in "${opt_sets[@]}"; do
    cells=$((cells + 1))
    # shellcheck disable=SC2086
    launch host_cell "$real" "$rtk" "$pinned" "$cells" $opts
    mine+=("$cells")
  done
  while read -r name cc opt extra run kernels; do
    case $kernels in native) kernels=$native_kernels ;; emulated) kernels=$emulated_kernels ;; esac
    cells=$((cells + 1))
    mine+=("$cells")
    launch core_cell "$real" "$pinned" "$cells" "$name" "$cc" "$opt" "$extra" "$run" "$kernels"
  done <<'VARIANTS'
gcc-O0 gcc -O0 -static env default
gcc-O1 gcc -O1 -static env default
gcc-O2 gcc -O2 -static env native
gcc-O3 gcc -O3 -static env default
gcc-Os gcc -Os -static env default
clang-O0 clang -O0 -static env default
clang-O1 clang -O1 -static env default
clang-O2 clang -O2 -static env native
clang-O3 clang -O3 -static env default
clang-Os clang -Os -static env default
i686-gcc-O2 gcc -O2 -m32_-msse2_-mfpmath=sse_-static i686 emulated
aarch64-gcc-O2 aarch64-linux-gnu-gcc -O2 -static qemu-aarch64 default
riscv64-gcc-O2 riscv64-linux-gnu-gcc -O2 -static qemu-riscv64 default
s390x-gcc-O2 s390x-linux-gnu-gcc -O2 -static qemu-s390x default
VARIANTS
  wait
  echo "determinism ($real, ${size}x${size}, against $pinned):"
  for i in "${mine[@]}"; do sed 's/^/  /' "$work/result/$i"; done
done
passed=$(cat "$work"/result/* | grep -c '^ok ' || true)
failed=$(cat "$work"/result/* | grep -c '^DIFFERS ' || true)
echo "determinism: $passed passed, $failed failed"
[ "$failed" = 0 ]
