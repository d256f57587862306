#!/usr/bin/env bash
# How close the fixed-point build comes to the double build: renders every golden scene
# with both and prints rtk compare's PSNR and worst difference, one row per scene.
# Scenes marked @fixed-small in tests/golden/scenes.txt are compared at 128x128.
# A scene under MIN_PSNR dB (default 80) or with a channel more than MAX_DIFF levels
# apart (default 1) fails; part of make check. Ends "fixed-vs-double: N passed, M failed".
# Usage: targets/fixed_vs_double.sh [rtk options, e.g. --width 128 --height 128]
set -euo pipefail
min_psnr=${MIN_PSNR:-80} max_diff=${MAX_DIFF:-1}
cd "$(dirname "$0")/.."
corpus=${RTK_SHARED:-../shared}/cse457/assets/trace
make -s build/rtk
make -s RT_REAL=fixed build-fixed/rtk
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "fixed build against double build: each scene >= $min_psnr dB, at most $max_diff level apart"
printf '%-40s %10s %8s %10s\n' scene "PSNR dB" "max" "within 1"
passed=0 failed=0
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
  if python3 - "$scene" "$work/m.json" "$min_psnr" "$max_diff" <<'PY'
import json, sys
m = json.load(open(sys.argv[2]))
psnr = m["psnr"] if m["psnr"] == "inf" else "%.2f" % m["psnr"]
low = m["psnr"] != "inf" and m["psnr"] < float(sys.argv[3])
far = m["max_diff"] > int(sys.argv[4])
print("%-40s %10s %8d %9.3f%%%s" % (sys.argv[1], psnr, m["max_diff"], m["within_pct"]["1"],
                                    "  FAILED" if low or far else ""))
sys.exit(1 if low or far else 0)
PY
  then passed=$((passed + 1)); else failed=$((failed + 1)); fi
done <tests/golden/scenes.txt
echo "fixed-vs-double: $passed passed, $failed failed"
[ "$failed" = 0 ]
