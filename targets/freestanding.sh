#!/usr/bin/env bash
# The core's freestanding contract, checked on the object code:
#   - core/ includes no header but stdint.h, stddef.h and stdbool.h;
#   - built with -ffreestanding -fno-builtin -nostdlib, for both scalar types, the archive
#     needs no symbol from outside but memcpy, memset and memmove (nm -u);
#   - the fixed build compiles with -mgeneral-regs-only (no floating-point register can
#     be used) on x86-64 and, for the bare-metal target, for a Cortex-M3 without an FPU.
# Every core source must compile and its object be in the archive: one that does not
# fails its line (a file left out would hide whatever it uses). A missing toolchain is
# installed with apt-get, and is a failure when it still cannot be found.
# Prints one line per check and "freestanding: N passed, M failed".
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
result() { if [ "$2" = 0 ]; then passed=$((passed + 1)); echo "  ok      $1"; else failed=$((failed + 1)); echo "  FAILED  $1"; fi; }

if ! command -v arm-none-eabi-gcc >/dev/null; then
  sudo=; [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get install -y -qq gcc-arm-none-eabi >/dev/null || true
fi

bad_includes=$(grep -hoE '#include[[:space:]]*<[^>]+>' core/*.c core/*.h | grep -vE '<(stdint|stddef|stdbool)\.h>' || true)
[ -z "$bad_includes" ]; result "core includes only stdint.h stddef.h stdbool.h" $?

# core_object NAME REAL CC FLAGS...: compiles every core source of REAL into
# $work/NAME/ and links them into one relocatable object $work/NAME.o (so symbols one
# member defines for another resolve). Fails, saying why, when the compiler is missing,
# any source fails to compile or any object is absent from the link.
core_object() {
  local name=$1 real=$2 cc=$3 src sources=() compiled=0
  shift 3
  command -v "$cc" >/dev/null || { echo "    $cc is not installed"; return 1; }
  read -ra sources <<<"$(make -s core-sources RT_REAL="$real")"
  [ ${#sources[@]} -gt 0 ] || { echo "    make core-sources listed nothing"; return 1; }
  mkdir -p "$work/$name"
  for src in "${sources[@]}"; do
    if "$cc" -std=c11 -O2 -ffreestanding -fno-builtin -nostdlib -ffp-contract=off -fno-math-errno -Iinclude "$@" \
      -c "$src" -o "$work/$name/$(basename "$src" .c).o" 2>"$work/$name.err"; then
      compiled=$((compiled + 1))
    else
      echo "    $src does not compile:"; sed 's/^/      /' "$work/$name.err" | head -5
    fi
  done
  [ "$compiled" = ${#sources[@]} ] || { echo "    $compiled of ${#sources[@]} sources compiled"; return 1; }
  local objects
  objects=$(find "$work/$name" -name '*.o' | wc -l)
  [ "$objects" = ${#sources[@]} ] || { echo "    $objects objects for ${#sources[@]} sources"; return 1; }
  "${cc%gcc}ld" -r -o "$work/$name.o" "$work/$name"/*.o
}
# undefined_within NAME NM: the linked object needs nothing but memcpy, memset, memmove.
undefined_within() {
  local extra
  extra=$("$2" -u "$work/$1.o" | awk '/ U /{print $2}' | sort -u | grep -vxE 'memcpy|memset|memmove' || true)
  [ -z "$extra" ] || echo "    undefined: $(echo $extra)"
  [ -z "$extra" ]
}
# check LABEL NAME REAL CC NM FLAGS...: one line per build.
check() {
  local label=$1 name=$2 real=$3 cc=$4 nm=$5 rc=0
  shift 5
  core_object "$name" "$real" "$cc" "$@" && undefined_within "$name" "$nm" || rc=1
  result "$label" $rc
}

check "double core (x86-64): every file compiles; nm -u within memcpy memset memmove" \
  double-x86_64 double gcc nm
check "fixed core (x86-64, -mgeneral-regs-only): every file compiles; nm -u within memcpy memset memmove" \
  fixed-x86_64 fixed gcc nm -DRT_REAL_FIXED -mgeneral-regs-only
check "fixed core (Cortex-M3, soft float): every file compiles; nm -u within memcpy memset memmove" \
  fixed-cortex-m3 fixed arm-none-eabi-gcc arm-none-eabi-nm -DRT_REAL_FIXED -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
echo "freestanding: $passed passed, $failed failed"
[ "$failed" = 0 ]
