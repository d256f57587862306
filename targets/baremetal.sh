#!/usr/bin/env bash
# Builds the fixed core with targets/cortex-m into an image for the MPS2 AN385 board
# (Cortex-M3, no FPU), with scenes/baremetal.yaml linked in as an `rtk pack` blob, runs
# it under qemu-system-arm, and checks that the render hash it prints over semihosting
# equals the one pinned in tests/golden/baremetal.sha256 and the host fixed build's.
# Prints the board's report and "baremetal: N passed, M failed".
#   targets/baremetal.sh            check
#   targets/baremetal.sh --bless    re-pin from the host fixed build (make bless RT_REAL=fixed)
set -euo pipefail
cd "$(dirname "$0")/.."
out=build-baremetal
scene=scenes/baremetal.yaml
pinned=tests/golden/baremetal.sha256
if [ "${1:-}" = --bless ]; then
  make -s RT_REAL=fixed build-fixed/rtk
  echo "$(build-fixed/rtk render "$scene" --hash --quiet)  $scene" >"$pinned"
  echo "baremetal: wrote the hash of $scene to $pinned"
  exit 0
fi
missing=()
command -v arm-none-eabi-gcc >/dev/null || missing+=(gcc-arm-none-eabi)
command -v qemu-system-arm >/dev/null || missing+=(qemu-system-arm)
if [ ${#missing[@]} -gt 0 ]; then
  sudo=; [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
make -s RT_REAL=fixed build-fixed/rtk
mkdir -p "$out"
build-fixed/rtk pack "$scene" -o "$out/scene.rtscene"
# objcopy names the blob's symbols after its file name: _binary_scene_rtscene_start/_end.
(cd "$out" && arm-none-eabi-objcopy -I binary -O elf32-littlearm -B arm scene.rtscene scene.o)
arm-none-eabi-gcc -std=c11 -O2 -g -mcpu=cortex-m3 -mthumb -mfloat-abi=soft \
  -ffreestanding -fno-builtin -nostdlib -ffp-contract=off -DRT_REAL_FIXED -Iinclude -Icore \
  -Wall -Wextra -T targets/cortex-m/mps2.ld \
  targets/cortex-m/*.c $(make -s core-sources RT_REAL=fixed) "$out/scene.o" -lgcc \
  -o "$out/rtk.elf"
arm-none-eabi-size "$out/rtk.elf"
report=$(timeout 600 qemu-system-arm -M mps2-an385 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native -kernel "$out/rtk.elf" 2>&1)
echo "$report"
board=$(echo "$report" | head -1)
host=$(build-fixed/rtk render "$scene" --hash --quiet)
want=$(awk -v s="$scene" '$2 == s { print $1 }' "$pinned")
if [ "$board" = "$want" ] && [ "$host" = "$want" ]; then
  echo "baremetal: 1 passed, 0 failed"
else
  echo "baremetal: board hash $board, host fixed build $host, pinned ${want:-(none)} in $pinned" >&2
  echo "baremetal: 0 passed, 1 failed"
  exit 1
fi
