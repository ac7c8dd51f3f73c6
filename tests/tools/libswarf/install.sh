#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# install.sh BUILD_DIR SOURCE_DIR PREFIX CC CXX -- `cmake --install` into a
# fresh PREFIX and use it as someone else would:
#   - the layout (headers under include/swarf/, libswarf.so with its SONAME
#     beside libswarf.a, swarf.pc, the CMake package, bin/swarf, swarf.1, the
#     Python module);
#   - libswarf.so exports exactly the SWARF_API functions its headers declare;
#   - every public header compiles on its own, as C11 and as C++17, with
#     -pedantic -Wall -Wextra -Werror;
#   - consumer.c built with pkg-config (swarf.pc shared, seeing no other
#     package's .pc file, as without the dependencies' -dev packages; and
#     swarf-static.pc) and with CMake's find_package (swarf::swarf,
#     swarf::swarf_static) runs in a thread with a 256 KB stack and checks a
#     simulated volume against the analytic one;
#   - the installed command simulates (its stock module found under LIBDIR/swarf/);
#   - the man page formats without warnings and holds every command;
#   - the .vdb reader program (LIBEXECDIR/swarf/swarf-vdb-read) is found by
#     the installed swarf and by the Python module through libswarf.so from
#     a copy of the prefix moved outside the build tree (so only the paths
#     relative to the installation can find it), and its absence is an error
#     that names it.
# PREFIX stays for the Python test (FIXTURES_SETUP swarf_install). (No `| grep -q`:
# under pipefail its early exit fails the pipe.)
set -euo pipefail
build=$1 src=$2 prefix=$3 cc=$4 cxx=$5
work=$prefix.work
rm -rf "$prefix" "$work"
mkdir -p "$work"
fail() { echo "install.sh: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log" || {
  cat "$work/install.log"; fail "cmake --install failed"; }

# ---- Layout ------------------------------------------------------------------
pc=$(find "$prefix" -name swarf.pc -path '*/pkgconfig/*')
[ -n "$pc" ] || fail "no swarf.pc installed"
libdir=$(dirname "$(dirname "$pc")")
for f in include/swarf/swarf.h include/swarf/swarf_version.h include/swarf/swarf_sim.h \
         include/swarf/swarf_status.h include/swarf/status.def include/swarf/stock.h \
         bin/swarf share/man/man1/swarf.1 lib/python3/dist-packages/swarf/__init__.py \
         lib/python3/dist-packages/swarf/_abi.py; do
  [ -f "$prefix/$f" ] || fail "$f not installed"
done
for f in libswarf.a libswarf.so cmake/swarf/swarfConfig.cmake cmake/swarf/swarfConfigVersion.cmake \
         cmake/swarf/swarfTargets.cmake; do
  [ -e "$libdir/$f" ] || fail "$libdir/$f not installed"
done
version=$(sed -n 's/^#define SWARF_VERSION_STRING "\(.*\)"$/\1/p' "$prefix/include/swarf/swarf_version.h")
[ -n "$version" ] || fail "no SWARF_VERSION_STRING in swarf_version.h"
soname=$(readelf -d "$libdir/libswarf.so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
case "$version" in
  0.*) want=libswarf.so.$(echo "$version" | cut -d. -f1,2) ;;
  *) want=libswarf.so.$(echo "$version" | cut -d. -f1) ;;
esac
[ "$soname" = "$want" ] || fail "SONAME $soname, expected $want"
[ -e "$libdir/$soname" ] || fail "$soname not installed"
[ "$(readlink -f "$libdir/libswarf.so")" = "$(readlink -f "$libdir/libswarf.so.$version")" ] ||
  fail "libswarf.so does not lead to libswarf.so.$version"
ar t "$libdir/libswarf.a" | grep '^sim\.c\.o$' >/dev/null || fail "libswarf.a lacks the driver"
ar t "$libdir/libswarf.a" | grep '^io\.cc\.o$' >/dev/null || fail "libswarf.a lacks the stock"
ar t "$libdir/libswarf.a" | grep '^interp\.c\.o$' >/dev/null || fail "libswarf.a lacks the interpreter"

# ---- Exports: exactly the declared API -----------------------------------------
grep -h '^SWARF_API ' "$prefix"/include/swarf/*.h | sed 's/(.*//; s/.*[ *]//' | sort -u \
  >"$work/declared"
nm -D --defined-only "$libdir/libswarf.so" | awk '$2 ~ /^[TWDBRV]$/ {print $3}' | sort -u \
  >"$work/exported"
[ "$(wc -l <"$work/declared")" -gt 100 ] || fail "only $(wc -l <"$work/declared") declarations found"
if ! diff "$work/declared" "$work/exported" >"$work/exports.diff"; then
  echo "< declared in the headers but not exported, > exported but not declared:" >&2
  cat "$work/exports.diff" >&2
  fail "libswarf.so's exports differ from the SWARF_API declarations"
fi
echo "exports: $(wc -l <"$work/exported") functions, all declared SWARF_API"

# ---- Each header alone, as C and as C++ ----------------------------------------
for h in "$prefix"/include/swarf/*.h; do
  name=$(basename "$h")
  echo "#include <swarf/$name>" >"$work/h.c"
  "$cc" -std=c11 -pedantic -Wall -Wextra -Werror -fsyntax-only -I"$prefix/include" "$work/h.c" ||
    fail "$name does not compile alone as C11"
  "$cxx" -x c++ -std=c++17 -pedantic -Wall -Wextra -Werror -fsyntax-only -I"$prefix/include" \
    "$work/h.c" || fail "$name does not compile alone as C++17"
done
echo "headers: $(ls "$prefix"/include/swarf/*.h | wc -l) compile alone as C11 and C++17"

# ---- pkg-config ---------------------------------------------------------------
# Only swarf's own .pc files are visible (PKG_CONFIG_LIBDIR), as on a machine without
# the dependencies' -dev packages: a shared link needs nothing of theirs.
export PKG_CONFIG_LIBDIR=$libdir/pkgconfig
[ "$(pkg-config --modversion swarf)" = "$version" ] || fail "pkg-config --modversion"
# shellcheck disable=SC2046
set -- $(pkg-config --cflags swarf)
[ $# -eq 1 ] && [ "$(realpath "${1#-I}")" = "$(realpath "$prefix/include")" ] ||
  fail "pkg-config --cflags swarf: $* (only swarf's include folder)"
# shellcheck disable=SC2046
set -- $(pkg-config --libs swarf)
[ $# -eq 2 ] && [ "$(realpath "${1#-L}")" = "$(realpath "$libdir")" ] && [ "$2" = -lswarf ] ||
  fail "pkg-config --libs swarf: $* (only -L LIBDIR -lswarf)"
pkg-config --static --libs swarf | grep -- '-lopenvdb' >/dev/null || fail "swarf.pc: no -lopenvdb in Libs.private"
pkg-config --static --libs swarf | grep -- '-lgmp' >/dev/null || fail "swarf.pc: no -lgmp in Libs.private"
# shellcheck disable=SC2046
"$cc" -std=c11 -Wall -Werror -pthread -o "$work/pc_shared" "$src/tests/tools/libswarf/consumer.c" \
  $(pkg-config --cflags --libs swarf) -lm -Wl,-rpath,"$libdir"
ldd "$work/pc_shared" >"$work/ldd_shared"
grep -q "$soname" "$work/ldd_shared" || fail "pc_shared does not use $soname"
"$work/pc_shared"
# Static: swarf-static.pc names libswarf.a and what it needs (pkg-config --static swarf
# cannot keep the linker from taking libswarf.so, which -lswarf finds first).
# shellcheck disable=SC2046
"$cc" -std=c11 -Wall -Werror -pthread -o "$work/pc_static" "$src/tests/tools/libswarf/consumer.c" \
  $(pkg-config --cflags --libs swarf-static)
ldd "$work/pc_static" >"$work/ldd_static"
if grep -q libswarf "$work/ldd_static"; then fail "pc_static uses the shared library"; fi
"$work/pc_static"
unset PKG_CONFIG_LIBDIR

# ---- CMake package --------------------------------------------------------------
cmake -S "$src/tests/tools/libswarf" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release \
  >"$work/cmake.log" || { cat "$work/cmake.log"; fail "find_package(swarf) project failed"; }
cmake --build "$work/cmake" >"$work/build.log" 2>&1 || {
  cat "$work/build.log"; fail "building the find_package(swarf) consumer failed"; }
"$work/cmake/consumer_shared"
"$work/cmake/consumer_static"
"$work/cmake/consumer_cxx"
# A version the package is not compatible with is refused.
sed 's/find_package(swarf 0.1 REQUIRED)/find_package(swarf 9.0 REQUIRED)/' \
  "$src/tests/tools/libswarf/CMakeLists.txt" >"$work/CMakeLists.v9"
mkdir -p "$work/v9" && cp "$work/CMakeLists.v9" "$work/v9/CMakeLists.txt"
if cmake -S "$work/v9" -B "$work/v9/build" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null 2>&1; then
  fail "find_package(swarf 9.0) accepted version $version"
fi

# ---- The command and its man page -------------------------------------------------
"$prefix/bin/swarf" --help >/dev/null || fail "installed swarf --help"
# The command loads its stock module from LIBDIR/swarf/ (stock/stock_module.h): a slot 20 mm
# long, 2 mm deep, flat D4 (20*4*2 + pi*2^2*2 = 185.13 mm^3).
ls "$libdir"/swarf/swarf_stock-"$version".so >/dev/null || fail "the stock module is not installed"
printf 'G21 G90\nT1 M6\nG0 X10 Y10 Z5\nG1 Z-2 F100\nG1 X30\nG0 Z5\nM2\n' >"$work/slot.ngc"
"$prefix/bin/swarf" simulate "$work/slot.ngc" --stock box:0,0,-10,40,20,0 --tool T1=flat,D4,L20 \
  --voxel 0.1 --out "$work/slot.vdb" >"$work/slot.out" || fail "installed swarf simulate"
removed=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$work/slot.out")
awk -v r="$removed" 'BEGIN { a = 160 + 8 * atan2(0, -1); exit !(r > a * 0.98 && r < a * 1.02) }' ||
  fail "installed swarf simulate: removed $removed mm^3, analytic 185.13"
warnings=$(LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$prefix/share/man/man1/swarf.1" 2>&1)
[ -z "$warnings" ] || fail "swarf.1: $warnings"
page=$(LC_ALL=C.UTF-8 groff -man -Tutf8 -P-cbou "$prefix/share/man/man1/swarf.1")
for c in simulate parse info render envelope; do
  printf '%s\n' "$page" | grep "usage: swarf $c" >/dev/null || fail "swarf.1 lacks the $c command"
done
printf '%s\n' "$page" | grep -- "--stock box:" >/dev/null || fail "swarf.1 lacks simulate's options"
synopsis=$(printf '%s\n' "$page" | sed -n '/^SYNOPSIS/,/^DESCRIPTION/p' | tr '\n' ' ')
printf '%s\n' "$synopsis" | grep -- "--design" | grep -- "--report" >/dev/null ||
  fail "swarf.1's synopsis lacks --design and --report"
printf '%s\n' "$page" | grep "^ *4 *with --fail-on\|; 4 with" >/dev/null ||
  fail "swarf.1 lacks exit status 4"
for c in simulate parse info render compare envelope; do
  m="$prefix/share/man/man1/swarf-$c.1"
  [ -f "$m" ] || fail "swarf-$c.1 not installed"
  warnings=$(LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$m" 2>&1)
  [ -z "$warnings" ] || fail "swarf-$c.1: $warnings"
  LC_ALL=C.UTF-8 groff -man -Tutf8 -P-cbou "$m" | grep "usage: swarf $c" >/dev/null ||
    fail "swarf-$c.1 lacks its usage"
done
# Section 3: libswarf.3 from the headers, and a page for every call the library exports.
m3="$prefix/share/man/man3"
warnings=$(LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$m3/libswarf.3" 2>&1)
[ -z "$warnings" ] || fail "libswarf.3: $warnings"
LC_ALL=C.UTF-8 groff -man -Tutf8 -P-cbou "$m3/libswarf.3" | grep "swarf_sim_config_new(void);" >/dev/null ||
  fail "libswarf.3 lacks swarf_sim_config_new"
missing=""
for sym in $(nm -D --defined-only "$libdir/libswarf.so" | awk '$2 == "T" && $3 ~ /^swarf_/ {print $3}'); do
  [ -f "$m3/$sym.3" ] || missing="$missing $sym"
done
[ -z "$missing" ] || fail "exported calls without a man page:$missing"
for f in README.md simulate.md modbus.md libswarf.md; do
  [ -f "$prefix/share/doc/swarf/$f" ] || fail "share/doc/swarf/$f not installed"
done
# ---- The .vdb reader program, from a moved copy of the prefix ----------------------
[ -x "$prefix/libexec/swarf/swarf-vdb-read" ] || fail "libexec/swarf/swarf-vdb-read not installed"
moved=$(mktemp -d /tmp/swarf-moved-prefix.XXXXXX)
trap 'rm -rf "$moved"' EXIT
cp -a "$prefix/." "$moved/"
"$moved/bin/swarf" simulate "$src/fixtures/demo.ngc" --stock box:0,0,-20,80,60,0 \
  --tool T1=flat,D6,L24 --tool T2=ball,D3.175,L20 --voxel 1 --out "$moved/demo.vdb" --quiet
unset SWARF_VDB_READER SWARF_VDB_ISOLATE
info=$("$moved/bin/swarf" info "$moved/demo.vdb") || fail "moved swarf info: the reader not found"
cli_volume=$(printf '%s\n' "$info" | sed -n 's/^volume \([0-9.]*\) mm^3$/\1/p')
py_volume=$(PYTHONPATH="$moved/lib/python3/dist-packages" /usr/bin/python3 -c '
import sys, swarf
with swarf.Stock.read(sys.argv[1]) as s: print("%.3f" % s.volume)' "$moved/demo.vdb") ||
  fail "the moved Python module cannot read a .vdb"
[ -n "$cli_volume" ] && [ "$cli_volume" = "$py_volume" ] ||
  fail "moved prefix: swarf info's volume '$cli_volume', the Python module's '$py_volume'"
rm "$moved/libexec/swarf/swarf-vdb-read"
if out=$("$moved/bin/swarf" info "$moved/demo.vdb" 2>&1); then fail "read a .vdb without the reader"; fi
case "$out" in
  *"swarf-vdb-read was not found"*) ;;
  *) fail "without the reader: '$out'" ;;
esac
echo "reader: found from bin/ and from libswarf.so in a moved prefix ($py_volume mm^3)"

echo "install.sh: all checks passed (libswarf $version in $prefix)"
