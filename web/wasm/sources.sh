#!/usr/bin/env bash
# Unpacks the Debian sources of the libraries the WebAssembly build compiles (libyaml,
# libspng, zlib) into DIR, at the versions pinned below: the same versions as the -dev
# packages the native build links. Adds a deb-src entry (a copy of the system's Debian
# deb entries) when apt has none, so a fresh machine can run `apt-get source`.
#   web/wasm/sources.sh DIR
set -euo pipefail
dir=$1
# package=version, as `apt-cache policy libyaml-dev libspng-dev zlib1g-dev` shows them installed.
pins=(libyaml=0.2.5-1 libspng=0.7.3-3 zlib=1:1.2.13.dfsg-1)
# The folder each unpacks to.
dirs=(libyaml-0.2.5 libspng-0.7.3 zlib-1.2.13.dfsg)

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

have_all() {
  for i in "${!pins[@]}"; do
    [ -f "$dir/${dirs[$i]}/.rtk-version" ] && [ "$(cat "$dir/${dirs[$i]}/.rtk-version")" = "${pins[$i]#*=}" ] || return 1
  done
}
have_all && exit 0

command -v dpkg-source >/dev/null || as_root apt-get install -y -qq dpkg-dev
if ! grep -rqs '^Types:.*deb-src\|^deb-src ' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  src=/etc/apt/sources.list.d/debian.sources
  [ -f "$src" ] || { echo "sources.sh: no $src to derive a deb-src entry from; add one for bookworm" >&2; exit 1; }
  echo "sources.sh: adding deb-src entries (a copy of $src)"
  sed 's/^Types: deb$/Types: deb-src/' "$src" | as_root tee /etc/apt/sources.list.d/rtk-deb-src.sources >/dev/null
  as_root apt-get update -qq
fi

mkdir -p "$dir"
cd "$dir"
rm -rf "${dirs[@]}"
apt-get source -qq "${pins[@]}" 2>&1 | grep -v '^W: Download is performed unsandboxed' || true
for i in "${!pins[@]}"; do
  name=${pins[$i]%%=*} want=${pins[$i]#*=} d=${dirs[$i]}
  [ -d "$d" ] || { echo "sources.sh: apt-get source $name=$want did not unpack $d" >&2; exit 1; }
  got=$(dpkg-parsechangelog -l "$d/debian/changelog" -S Version)
  [ "$got" = "$want" ] || { echo "sources.sh: $d is $name $got, want $want" >&2; exit 1; }
  echo "$got" >"$d/.rtk-version"
  echo "sources.sh: $name $got in $dir/$d"
done
