#!/usr/bin/env bash
# The core's freestanding contract, checked on the object code:
#   - core/ includes no header but stdint.h, stddef.h and stdbool.h;
#   - built with -ffreestanding -fno-builtin -nostdlib, for both scalar types, the archive
#     needs no symbol from outside but memcpy, memset and memmove (nm -u);
#   - the fixed build compiles with -mgeneral-regs-only (no floating-point register can
#     be used) on x86-64 and, for the bare-metal target, for a Cortex-M3 without an FPU.
# Prints one line per check and "freestanding: N passed, M failed".
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
result() { if [ "$2" = 0 ]; then passed=$((passed + 1)); echo "  ok      $1"; else failed=$((failed + 1)); echo "  FAILED  $1"; fi; }

bad_includes=$(grep -hoE '#include[[:space:]]*<[^>]+>' core/*.c core/*.h | grep -vE '<(stdint|stddef|stdbool)\.h>' || true)
[ -z "$bad_includes" ]; result "core includes only stdint.h stddef.h stdbool.h" $?

# archive NAME CC FLAGS...: compiles the core into $work/NAME.a and, linked into one
# relocatable object (so symbols one member defines for another resolve), $work/NAME.o.
archive() {
  local name=$1 cc=$2 real=double
  shift 2
  case " $* " in *" -DRT_REAL_FIXED "*) real=fixed ;; esac
  mkdir -p "$work/$name"
  for src in $(make -s core-sources RT_REAL="$real"); do
    "$cc" -std=c11 -O2 -ffreestanding -fno-builtin -nostdlib -ffp-contract=off -fno-math-errno "$@" \
      -c "$src" -o "$work/$name/$(basename "$src" .c).o"
  done
  ar rcs "$work/$name.a" "$work/$name"/*.o
  "${cc%gcc}ld" -r -o "$work/$name.o" "$work/$name"/*.o
}
check_symbols() { # NAME NM
  local extra
  extra=$("$2" -u "$work/$1.o" | awk '/ U /{print $2}' | sort -u | grep -vxE 'memcpy|memset|memmove' || true)
  [ -z "$extra" ] || echo "    undefined: $(echo $extra)"
  [ -z "$extra" ]
}

archive double-x86_64 gcc
check_symbols double-x86_64 nm; result "double core (x86-64): nm -u within memcpy memset memmove" $?
if archive fixed-x86_64 gcc -DRT_REAL_FIXED -mgeneral-regs-only 2>"$work/err"; then
  check_symbols fixed-x86_64 nm; result "fixed core (x86-64, -mgeneral-regs-only): nm -u within memcpy memset memmove" $?
else
  cat "$work/err"; result "fixed core compiles with -mgeneral-regs-only" 1
fi
if command -v arm-none-eabi-gcc >/dev/null; then
  if archive fixed-cortex-m3 arm-none-eabi-gcc -DRT_REAL_FIXED -mcpu=cortex-m3 -mthumb -mfloat-abi=soft 2>"$work/err"; then
    check_symbols fixed-cortex-m3 arm-none-eabi-nm; result "fixed core (Cortex-M3, soft float): nm -u within memcpy memset memmove" $?
  else
    cat "$work/err"; result "fixed core compiles for Cortex-M3" 1
  fi
fi
echo "freestanding: $passed passed, $failed failed"
[ "$failed" = 0 ]
