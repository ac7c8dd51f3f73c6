#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# stock_module.sh SWARF SOURCE_DIR -- the `swarf` command loads the stock module (OpenVDB) on
# first use only (stock/stock_module.h):
#   - the command does not link OpenVDB (readelf: no libopenvdb, libtbb among its NEEDED);
#   - stock/stock_api.def lists exactly the SWARF_API functions of stock.h and stock_output.h;
#   - `swarf parse` loads neither the module nor OpenVDB (the loader's own trace, LD_DEBUG);
#   - `swarf simulate` loads the module and cuts a slot of the analytic volume;
#   - a copy of the command alone still parses and simulates (the module where the build put
#     it), a copy with the module beside it loads that one;
#   - a module that cannot be loaded (SWARF_STOCK_MODULE names none) is a clear error, exit
#     status 2 and no output file.
set -euo pipefail
swarf=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "stock_module.sh: $*" >&2; exit 1; }

needed=$(readelf -d "$swarf" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
echo "NEEDED: $(echo $needed)"
case " $(echo $needed) " in
  *libopenvdb* | *libtbb*) fail "swarf links OpenVDB or TBB" ;;
esac

grep -h '^SWARF_API ' "$src/stock/stock.h" "$src/stock/stock_output.h" | sed 's/(.*//; s/.*[ *]//' |
  sort >"$work/declared"
sed -n 's/^\(STATUS\|VOID\)(\([a-z_]*\),.*/\2/p; s/^VALUE([^,]*, \([a-z_]*\),.*/\1/p' \
  "$src/stock/stock_api.def" | sort >"$work/listed"
[ "$(wc -l <"$work/declared")" -gt 40 ] || fail "only $(wc -l <"$work/declared") declarations"
diff "$work/declared" "$work/listed" || fail "stock_api.def differs from the headers' SWARF_API"

# A slot 20 mm long, 2 mm deep, with a flat D4 cutter: 20*4*2 + pi*2^2*2 = 185.13 mm^3.
printf 'G21 G90 G17\nT1 M6\nG0 X10 Y10 Z5\nG1 Z-2 F100\nG1 X30\nG0 Z5\nM2\n' >"$work/slot.ngc"
LD_DEBUG=files "$swarf" parse "$work/slot.ngc" --quiet 2>"$work/parse.trace" ||
  fail "swarf parse failed"
if grep -E 'file=[^ ]*(libopenvdb|swarf_stock)' "$work/parse.trace" >/dev/null; then
  fail "swarf parse loaded the stock module or OpenVDB"
fi
LD_DEBUG=files "$swarf" simulate "$work/slot.ngc" --stock box:0,0,-10,40,20,0 --tool T1=flat,D4,L20 \
  --voxel 0.1 --out "$work/slot.vdb" >"$work/sim.out" 2>"$work/sim.trace" ||
  { cat "$work/sim.out"; fail "swarf simulate failed"; }
grep -E 'file=[^ ]*swarf_stock-[^ ]*\.so' "$work/sim.trace" >/dev/null || fail "simulate did not load the module"
removed=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$work/sim.out")
awk -v r="$removed" 'BEGIN { a = 160 + 8 * atan2(0, -1); exit !(r > a * 0.98 && r < a * 1.02) }' ||
  fail "removed $removed mm^3, analytic 185.13"
[ -s "$work/slot.vdb" ] || fail "no .vdb written"
echo "simulate through the module: removed $removed mm^3 (analytic 185.13)"

# A copy of the command alone finds the module where the build put it; a copy with its
# module beside it loads that one; a module that cannot be loaded is a clear error.
mkdir "$work/away" "$work/beside"
cp "$swarf" "$work/away/swarf"
cp "$swarf" "$(dirname "$(grep -o 'file=[^ ]*swarf_stock-[^ ]*\.so' "$work/sim.trace" | head -1 |
  cut -d= -f2)")"/swarf_stock-*.so "$work/beside/"
"$work/away/swarf" parse "$work/slot.ngc" --quiet >/dev/null || fail "parse needs the module"
"$work/away/swarf" simulate "$work/slot.ngc" --stock box:0,0,-10,40,20,0 --tool T1=flat,D4,L20 \
  --voxel 0.5 --out "$work/away/slot.vdb" >/dev/null || fail "a copy of swarf cannot simulate"
LD_DEBUG=files "$work/beside/swarf" simulate "$work/slot.ngc" --stock box:0,0,-10,40,20,0 \
  --tool T1=flat,D4,L20 --voxel 0.5 --out "$work/beside/slot.vdb" >/dev/null 2>"$work/beside.trace" ||
  fail "a copy of swarf with its module cannot simulate"
grep "file=$work/beside/swarf_stock-" "$work/beside.trace" >/dev/null ||
  fail "a copy of swarf did not load the module beside it"
set +e
SWARF_STOCK_MODULE=$work/none.so "$swarf" simulate "$work/slot.ngc" --stock box:0,0,-10,40,20,0 \
  --tool T1=flat,D4,L20 --voxel 0.5 --out "$work/none.vdb" >"$work/none.out" 2>"$work/none.err"
status=$?
set -e
[ "$status" = 2 ] || fail "without its module: exit status $status, expected 2"
grep 'cannot load the stock module' "$work/none.err" >/dev/null || fail "unclear error: $(cat "$work/none.err")"
[ ! -e "$work/none.vdb" ] || fail "an output was written without the module"
echo "without the module: $(cat "$work/none.err")"
echo "stock_module.sh: all checks passed"
