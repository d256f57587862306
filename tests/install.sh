#!/usr/bin/env bash
# `make check-install`: rtk installed as a library of its ecosystem, checked as a user
# would use it. Installs into a scratch DESTDIR + PREFIX, then
#   - builds examples/render_scene.c with `pkg-config --cflags --libs rtk`, against the
#     shared library and (--static) the static one, and runs both: each must print the
#     render hash `rtk render --hash` prints for the same scene;
#   - checks what was installed: rtk --version, the man page renders without warnings and
#     names every option every subcommand's --help lists, the bash completion loads and
#     offers every subcommand, librtk.so exports only rtk_ names;
#   - uninstalls and expects nothing left behind.
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=/opt/rtk-test
root=$work/root
failed=0
fail() { echo "  FAILED  $*"; failed=$((failed + 1)); }
ok() { echo "  ok      $*"; }

make -s install DESTDIR="$root" PREFIX="$prefix" >/dev/null
installed=$root$prefix
export PKG_CONFIG_PATH=$installed/lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$root
scene=scenes/demo.yaml
want=$(build/rtk render "$scene" --width 48 --height 48 --hash --quiet)

# shellcheck disable=SC2046
cc -std=c11 -Wall -Werror examples/render_scene.c -o "$work/shared" $(pkg-config --cflags --libs rtk)
got=$(LD_LIBRARY_PATH=$installed/lib "$work/shared" "$scene" "$work/a.png" 48 48)
[ "$got" = "$want" ] && ok "example against librtk.so (pkg-config): $got" || fail "librtk.so example printed '$got', rtk render '$want'"
# shellcheck disable=SC2046
cc -std=c11 -Wall -Werror examples/render_scene.c -o "$work/static" $(pkg-config --static --cflags --libs rtk | sed 's/-lrtk/-l:librtk.a/')
got=$("$work/static" "$scene" "$work/b.png" 48 48)
[ "$got" = "$want" ] && ok "example against librtk.a (pkg-config --static)" || fail "librtk.a example printed '$got'"
ldd "$work/static" | grep -q librtk && fail "the static example still needs librtk.so" || ok "the static example needs no librtk.so"
soname=$(objdump -p "$installed"/lib/librtk.so | awk '/SONAME/ {print $2}')
[ -n "$soname" ] && [ -e "$installed/lib/$soname" ] && ok "librtk.so has SONAME $soname" || fail "librtk.so's SONAME '$soname' is not installed"
exports=$(nm -D --defined-only "$installed"/lib/librtk.so | awk '$2 ~ /[TDBR]/ {print $3}' | grep -v '^rtk_' || true)
[ -z "$exports" ] && ok "librtk.so exports only rtk_ names" || fail "librtk.so exports $(echo $exports | head -c 200)"

# The manual's first example, cut from the installed rtk.h, compiles and runs as written.
sed -n '/^       #include <rtk.h>/,/^       }$/p' "$installed/include/rtk.h" | sed 's/^       //' >"$work/manual.c"
cp scenes/demo.yaml "$work/scene.yaml"
# shellcheck disable=SC2046
if cc -std=c11 -Wall -Werror "$work/manual.c" -o "$work/manual" $(pkg-config --cflags --libs rtk) &&
  got=$(cd "$work" && LD_LIBRARY_PATH=$installed/lib ./manual) &&
  [ "$got" = "$(build/rtk render scenes/demo.yaml --width 256 --height 256 --hash --quiet)" ] && [ -s "$work/out.png" ]; then
  ok "rtk.h's own example ($(wc -l <"$work/manual.c") lines) builds, runs and prints rtk render's hash"
else
  fail "rtk.h's example does not build or run as written"
fi

version=$("$installed/bin/rtk" --version)
case $version in "rtk $(pkg-config --modversion rtk) ("*"build; "*"; commit "*")") ok "rtk --version: $version" ;; *) fail "rtk --version printed '$version'" ;; esac

man=$installed/share/man/man1/rtk.1
warnings=$(LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$man" 2>&1 || true)
[ -z "$warnings" ] && ok "rtk(1) renders without warnings" || fail "rtk(1): $warnings"
text=$(LC_ALL=C.UTF-8 groff -man -Tascii -P-cbu "$man" 2>/dev/null)
commands=$(build/rtk --help | awk '/^commands:/ {on = 1; next} on && /^  [a-z]/ {print $1}')
missing=""
for c in $commands; do
  for o in $(build/rtk "$c" --help | grep -oE '(^|[ ,])--?[a-z][a-z-]*' | tr -d ' ,' | sort -u); do
    grep -qe "$o" <<<"$text" || missing="$missing $c:$o"
  done
  grep -qw "$c" <<<"$text" || missing="$missing $c"
done
[ -z "$missing" ] && ok "rtk(1) names every subcommand and option of --help" || fail "rtk(1) lacks$missing"

completion=$installed/share/bash-completion/completions/rtk
offered=$(PATH=$installed/bin:$PATH bash -c "source '$completion'; COMP_WORDS=(rtk ''); COMP_CWORD=1; _rtk; echo \${COMPREPLY[*]}")
for c in $commands; do grep -qw "$c" <<<"$offered" || fail "the completion does not offer '$c' (it offers: $offered)"; done
options=$(PATH=$installed/bin:$PATH bash -c "source '$completion'; COMP_WORDS=(rtk render --); COMP_CWORD=2; _rtk; echo \${COMPREPLY[*]}")
grep -qw -- --max-memory <<<"$options" && ok "bash completion offers the subcommands and their options" || fail "completion of 'rtk render --' gave: $options"

make -s uninstall DESTDIR="$root" PREFIX="$prefix" >/dev/null
left=$(find "$installed" -type f -o -type l)
[ -z "$left" ] && ok "uninstall removes every file" || fail "uninstall left: $left"

echo "install: $([ $failed = 0 ] && echo ok || echo "$failed failed")"
[ "$failed" = 0 ]
