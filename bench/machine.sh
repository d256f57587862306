#!/usr/bin/env bash
# Prints the CPU the benches ran on, for their tables' headers: lscpu's model name, its
# family and model numbers (virtual machines often hide which generation the name is)
# and whether it has AVX2 and AVX-512 (which decide rtk's and Embree's kernels).
set -eu
info=$(lscpu)
field() { sed -n "s/^$1: *//p" <<<"$info" | head -n1; }
flags=$(grep -m1 '^flags' /proc/cpuinfo 2>/dev/null || true)
has() { case " $flags " in *" $1 "*) echo "$2" ;; *) echo "no $2" ;; esac; }
printf '%s (family %s, model %s; %s, %s)\n' "$(field 'Model name')" "$(field 'CPU family')" "$(field 'Model')" \
    "$(has avx2 AVX2)" "$(has avx512f AVX-512)"
