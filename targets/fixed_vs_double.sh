#!/usr/bin/env bash
# How close the fixed-point build comes to the double build: renders every golden scene
# with both and prints rtk compare's PSNR and worst difference, one row per scene.
# Scenes marked @fixed-small in tests/golden/scenes.txt are compared at 128x128.
# Usage: targets/fixed_vs_double.sh [rtk options, e.g. --width 128 --height 128]
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=${RTK_SHARED:-../shared}/cse457/assets/trace
make -s build/rtk
make -s RT_REAL=fixed build-fixed/rtk
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-36s %10s %8s %10s\n' scene "PSNR dB" "max" "within 1"
while read -r scene opts; do
  case $scene in ''|'#'*) continue ;; esac
  opts=${opts//@fixed-small/--width 128 --height 128}
  path=$scene
  case $scene in corpus/*) path=$corpus/${scene#corpus/} ;; esac
  # shellcheck disable=SC2086
  build/rtk render "$path" -o "$work/d.ppm" --quiet $opts "$@"
  # shellcheck disable=SC2086
  build-fixed/rtk render "$path" -o "$work/f.ppm" --quiet $opts "$@"
  build/rtk compare "$work/f.ppm" "$work/d.ppm" --json >"$work/m.json" || true
  python3 - "$scene" "$work/m.json" <<'PY'
import json, sys
m = json.load(open(sys.argv[2]))
psnr = m["psnr"] if m["psnr"] == "inf" else "%.2f" % m["psnr"]
print("%-36s %10s %8d %9.3f%%" % (sys.argv[1], psnr, m["max_diff"], m["within_pct"]["1"]))
PY
done <tests/golden/scenes.txt
