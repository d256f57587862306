#!/usr/bin/env bash
# The determinism matrix: every build of the kernel must render every golden scene to
# the same bytes. For each scalar type given (double, fixed):
#   1. the host rtk at its default settings gives the reference hash of each scene
#      (rendered at SIZE x SIZE to keep the matrix fast; make check pins full size);
#   2. the host rtk with other thread counts and tile sizes must match it;
#   3. the core alone (targets/hash_driver.c reading `rtk pack` blobs), built with gcc
#      and clang at -O0/-O2/-O3, for i686 (-m32 -msse2 -mfpmath=sse) and for aarch64
#      (cross-compiled, run under qemu-user), must match it too. The i686 driver runs
#      natively where the kernel executes 32-bit binaries, else under qemu-i386 (some
#      kernels are built without 32-bit support: "Exec format error").
# Prints one line per variant, saying how its driver ran, and "determinism: N passed, M failed".
set -euo pipefail
cd "$(dirname "$0")/.."
reals=${*:-double fixed}
size=${SIZE:-64}
corpus=${RTK_SHARED:-../shared}/cse457/assets/trace
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0

need() { # installs Debian packages whose command or file is missing
  local missing=()
  while [ $# -gt 0 ]; do [ -e "$1" ] || command -v "$1" >/dev/null 2>&1 || missing+=("$2"); shift 2; done
  [ ${#missing[@]} = 0 ] && return
  local sudo=; [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}
need clang clang aarch64-linux-gnu-gcc gcc-aarch64-linux-gnu qemu-aarch64 qemu-user qemu-i386 qemu-user \
     /usr/lib32/libc.a libc6-dev-i386 /usr/lib/gcc/x86_64-linux-gnu/12/32/libgcc.a lib32gcc-12-dev

# Probed once: can this kernel execute a static i686 binary itself?
printf 'int main(void) { return 0; }\n' >"$work/probe.c"
gcc -m32 -static "$work/probe.c" -o "$work/probe-i686"
if "$work/probe-i686" 2>/dev/null; then i686_run=env; else i686_run=qemu-i386; fi
echo "i686 binaries run $([ "$i686_run" = env ] && echo natively || echo 'under qemu-i386 (the kernel cannot execute them)')"

scenes=()
while read -r scene _; do
  case $scene in ''|'#'*) continue ;; esac
  scenes+=("$scene")
done <tests/golden/scenes.txt
path_of() { local s=$1; case $s in corpus/*) echo "$corpus/${s#corpus/}" ;; *) echo "$s" ;; esac; }

check() { # check VARIANT REF_FILE OUT_FILE
  if cmp -s "$2" "$3"; then passed=$((passed + 1)); echo "  ok      $1"
  else failed=$((failed + 1)); echo "  DIFFERS $1"; diff "$2" "$3" | head -5 || true; fi
}

for real in $reals; do
  build=build; [ "$real" = fixed ] && build=build-fixed
  make -s RT_REAL="$real" "$build/rtk" >/dev/null
  rtk=$build/rtk
  echo "determinism ($real, ${size}x${size}):"
  ref=$work/$real.ref
  : >"$ref"
  for s in "${scenes[@]}"; do
    echo "$s $("$rtk" render "$(path_of "$s")" --width "$size" --height "$size" --hash --quiet)" >>"$ref"
    "$rtk" pack "$(path_of "$s")" --width "$size" --height "$size" -o "$work/$real.$(echo "$s" | tr / _).rtscene"
  done
  for opts in "--threads 1" "--threads 2 --tile 16" "--threads 7 --tile 5" "--threads 3 --tile 64"; do
    out=$work/out
    : >"$out"
    # shellcheck disable=SC2086
    for s in "${scenes[@]}"; do echo "$s $("$rtk" render "$(path_of "$s")" --width "$size" --height "$size" --hash --quiet $opts)" >>"$out"; done
    check "rtk $opts" "$ref" "$out"
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
    : >"$out"
    for s in "${scenes[@]}"; do
      # shellcheck disable=SC2086
      echo "$s $($run "$exe" "$work/$real.$(echo "$s" | tr / _).rtscene" 512)" >>"$out"
    done
    check "core $name ($([ "$run" = env ] && echo native || echo "$run"))" "$ref" "$out"
  done <<'VARIANTS'
gcc-O0 gcc -O0 -static env
gcc-O2 gcc -O2 -static env
gcc-O3 gcc -O3 -static env
clang-O0 clang -O0 -static env
clang-O2 clang -O2 -static env
clang-O3 clang -O3 -static env
i686-gcc-O2 gcc -O2 -m32_-msse2_-mfpmath=sse_-static i686
aarch64-gcc-O2 aarch64-linux-gnu-gcc -O2 -static qemu-aarch64
VARIANTS
done
echo "determinism: $passed passed, $failed failed"
[ "$failed" = 0 ]
