#!/usr/bin/env bash
# The determinism matrix: every build of the kernel must render every golden scene to
# the bytes pinned in tests/golden/matrix-<real>.sha256 (SIZE x SIZE renders, 64 by
# default; make check pins full size in tests/golden/<real>.sha256). For each scalar
# type given (double, fixed), each cell below is compared with the pinned hashes, so a
# change that moves every target together fails too:
#   1. the host rtk at its default settings, with other thread counts and tiles, and
#      with --no-bvh (every primitive tested);
#   2. the core alone (targets/hash_driver.c reading `rtk pack` blobs), built with gcc
#      and clang at -O0/-O1/-O2/-O3/-Os, for i686 (-m32 -msse2 -mfpmath=sse), and
#      cross-compiled for aarch64, riscv64 and big-endian s390x (run under qemu-user).
#      The i686 driver runs natively where the kernel executes 32-bit binaries, else
#      under qemu-i386 (some kernels are built without 32-bit support: "Exec format error").
# Prints one line per cell, saying how its driver ran, and "determinism: N passed, M failed".
#   targets/determinism.sh [double] [fixed]          check
#   targets/determinism.sh --bless [double] [fixed]  re-pin from the host rtk (make bless)
set -euo pipefail
cd "$(dirname "$0")/.."
bless=0
if [ "${1:-}" = --bless ]; then bless=1; shift; fi
reals=${*:-double fixed}
size=64 # the pinned size
corpus=${RTK_SHARED:-../shared}/cse457/assets/trace
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0

scenes=()
while read -r scene _; do
  case $scene in ''|'#'*) continue ;; esac
  scenes+=("$scene")
done <tests/golden/scenes.txt
path_of() { local s=$1; case $s in corpus/*) echo "$corpus/${s#corpus/}" ;; *) echo "$s" ;; esac; }
pinned_file() { echo "tests/golden/matrix-$1.sha256"; }

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

check() { # check CELL OUT_FILE: the cell's hashes against the pinned ones
  if cmp -s "$pinned" "$2"; then passed=$((passed + 1)); echo "  ok      $1"
  else failed=$((failed + 1)); echo "  DIFFERS $1 (from $pinned)"; diff "$pinned" "$2" | grep '^>' | head -5 || true; fi
}

for real in $reals; do
  build=build; [ "$real" = fixed ] && build=build-fixed
  make -s RT_REAL="$real" "$build/rtk" >/dev/null
  rtk=$build/rtk
  pinned=$(pinned_file "$real")
  [ -f "$pinned" ] || { echo "determinism: no pinned hashes in $pinned (make bless)" >&2; exit 1; }
  echo "determinism ($real, ${size}x${size}, against $pinned):"
  for s in "${scenes[@]}"; do
    "$rtk" pack "$(path_of "$s")" --width "$size" --height "$size" -o "$work/$real.$(echo "$s" | tr / _).rtscene"
  done
  # --no-bvh: every primitive tested, the whole image must not change (64x64: brute
  # force at full size takes minutes per mesh scene).
  for opts in "" "--threads 1" "--threads 2 --tile 16" "--threads 7 --tile 5" "--threads 3 --tile 64" "--no-bvh"; do
    out=$work/out
    # shellcheck disable=SC2086
    for s in "${scenes[@]}"; do
      echo "$("$rtk" render "$(path_of "$s")" --width "$size" --height "$size" --hash --quiet $opts)  $s"
    done >"$out"
    check "rtk ${opts:-(default threads and tiles)}" "$out"
  done
  core_src=$(make -s core-sources RT_REAL="$real")
  flags="-std=c11 -ffp-contract=off -fno-math-errno -Icore"
  [ "$real" = fixed ] && flags="$flags -DRT_REAL_FIXED"
  while read -r name cc opt extra run; do
    exe=$work/driver-$name
    extra=${extra//_/ }
    [ "$run" = i686 ] && run=$i686_run
    # shellcheck disable=SC2086
    $cc $flags $opt $extra targets/hash_driver.c $core_src -o "$exe"
    out=$work/out
    for s in "${scenes[@]}"; do
      # shellcheck disable=SC2086
      echo "$($run "$exe" "$work/$real.$(echo "$s" | tr / _).rtscene" 512)  $s"
    done >"$out"
    check "core $name ($([ "$run" = env ] && echo native || echo "$run"))" "$out"
  done <<'VARIANTS'
gcc-O0 gcc -O0 -static env
gcc-O1 gcc -O1 -static env
gcc-O2 gcc -O2 -static env
gcc-O3 gcc -O3 -static env
gcc-Os gcc -Os -static env
clang-O0 clang -O0 -static env
clang-O1 clang -O1 -static env
clang-O2 clang -O2 -static env
clang-O3 clang -O3 -static env
clang-Os clang -Os -static env
i686-gcc-O2 gcc -O2 -m32_-msse2_-mfpmath=sse_-static i686
aarch64-gcc-O2 aarch64-linux-gnu-gcc -O2 -static qemu-aarch64
riscv64-gcc-O2 riscv64-linux-gnu-gcc -O2 -static qemu-riscv64
s390x-gcc-O2 s390x-linux-gnu-gcc -O2 -static qemu-s390x
VARIANTS
done
echo "determinism: $passed passed, $failed failed"
[ "$failed" = 0 ]
