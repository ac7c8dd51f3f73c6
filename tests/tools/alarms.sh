#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# alarms.sh SWARF -- rapid moves that cut into material raise located alarms.
# The program below cuts a slot with G1, then: a G0 that runs on past the end
# of the slot into uncut stock (line 5: alarm), a G0 retract up through the
# hole the previous move cut (line 6: none), a G0 above the stock (line 7:
# none), a G0 plunge and a G0 traverse inside the stock (lines 8, 9: alarms),
# a G0 back along the slot that G1 cut (line 11: none, the slot is empty).
# The geometry decides each case by millimetres, far from the half-voxel
# depth threshold.
set -u
swarf=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; fi; }

printf 'G21 G0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y10\nG0 X35\nG0 Z5\nG0 X5 Y20\nG0 Z-1\nG0 X20\nG0 Z5\nG0 X10 Y10\nG0 Z-2\nG0 X25\nG0 Z5\nM2\n' > "$dir/p.ngc"
"$swarf" simulate "$dir/p.ngc" --stock box:0,0,-10,40,30,0 --tool T1=ball,D3,L12 --voxel 0.25 \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
rc=$?
cat "$dir/summary" "$dir/stderr"
ok "exits 0 (alarms are warnings)" '[ $rc -eq 0 ] && [ -s "$dir/out.vdb" ]'
ok "three alarms in the summary" 'grep -q "alarms 3 " "$dir/summary"'
ok "the lines of the alarms" '[ "$(grep -o "p.ngc:[0-9]*:[0-9]*: warning: rapid" "$dir/stderr" | cut -d: -f2 | tr "\n" " ")" = "5 8 9 " ]'

printf 'G21 G0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y10\nG0 Z5\nG0 X0 Y0\nM2\n' > "$dir/clean.ngc"
"$swarf" simulate "$dir/clean.ngc" --stock box:0,0,-10,40,30,0 --tool T1=ball,D3,L12 --voxel 0.25 \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
ok "a clean program has no alarm" 'grep -q "alarms 0 " "$dir/summary" && ! grep -q warning "$dir/stderr"'

# An empty spindle (CamBam posts write T0 M6): a slot with
# T1, then T0 M6 and feed moves into the stock (lines 9, 10: warned, nothing
# cut), then feed moves above it (line 12: none).
printf 'G21 G90
T1 M6
G0 X5 Y5 Z5
G1 Z-2 F300
G1 X15
G0 Z5
T0 M6
G0 X5 Y15
G1 Z-2 F300
G1 X15
G0 Z5
G1 X5 Y5
M2
' \
  > "$dir/t0.ngc"
"$swarf" simulate "$dir/t0.ngc" --stock box:0,0,-5,20,20,0 --tool T1=flat,D3 --voxel 0.25 \
  --out "$dir/t0.vdb" --report "$dir/t0.json" > "$dir/summary" 2> "$dir/stderr"
rc=$?
cat "$dir/summary" "$dir/stderr"
ok "T0: exits 0 (a warning)" '[ $rc -eq 0 ]'
ok "T0: the feed moves into the stock warned at lines 9 and 10" \
  '[ "$(grep -o "t0.ngc:[0-9]*:[0-9]*: warning: feed move with an empty spindle" "$dir/stderr" | cut -d: -f2 | tr "\n" " ")" = "9 10 " ]'
ok "T0: counted in the summary" 'grep -q "empty spindle (T0): 2" "$dir/summary"'
ok "T0: the report's alarm kind" \
  '/usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); sys.exit(not (r[\"summary\"][\"alarm_counts\"][\"no_tool\"] == 2 and [a[\"line\"] for a in r[\"alarms\"] if a[\"kind\"] == \"no_tool\"] == [9, 10]))" "$dir/t0.json"'
"$swarf" simulate "$dir/t0.ngc" --stock box:0,0,-5,20,20,0 --tool T1=flat,D3 --voxel 0.25 \
  --out "$dir/t0.vdb" --fail-on no-tool --quiet 2> "$dir/stderr"
rc=$?
ok "T0: --fail-on no-tool exits 4 (outputs written)" '[ $rc -eq 4 ] && [ -s "$dir/t0.vdb" ] && grep -q "fail-on no-tool" "$dir/stderr"'
# Tool selection per dialect (point 5). Fanuc and Haas controls hold their
# tool data: parse accepts any T (a note), simulate stops only at the first
# feed move of a tool it was not given, naming its change's line (T5 only
# moves in rapids: no error). LinuxCNC stops at the T word, as rs274 does.
printf '%%\nO1000\nG21 G90\nT5 M6\nG0 X5 Y5 Z5\nT1 M6\nG0 X5 Y5 Z2\nG1 Z-1 F100\nG1 X15\nG0 Z5\nT7 M6\nG0 X2\nG1 X1 F100\nM30\n%%\n' > "$dir/f.nc"
for d in fanuc haas; do
  "$swarf" parse --quiet --dialect $d "$dir/f.nc" > "$dir/out" 2> "$dir/stderr"
  ok "$d: parse accepts T5 and T7 with no table" '[ $? -eq 0 ] && grep -q "f.nc: 10 moves" "$dir/out"'
  "$swarf" simulate "$dir/f.nc" --dialect $d --stock box:0,0,-5,20,10,0 --tool T1=flat,D4 \
    --voxel 0.25 --out "$dir/f.vdb" > /dev/null 2> "$dir/stderr"
  rc=$?
  ok "$d: simulate stops at T7's first feed move (line 13), naming line 11, no output" \
    '[ $rc -eq 2 ] && grep -q "f.nc:13:1: a feed move with tool T7 (changed at line 11)" "$dir/stderr" && [ ! -e "$dir/f.vdb" ]'
done
sed 's/T7 M6/T1 M6/' "$dir/f.nc" > "$dir/g.nc"
"$swarf" simulate "$dir/g.nc" --dialect fanuc --stock box:0,0,-5,20,10,0 --tool T1=flat,D4 \
  --voxel 0.25 --out "$dir/g.vdb" > "$dir/summary" 2> "$dir/stderr"
ok "fanuc: T5 that never feeds is no error" '[ $? -eq 0 ] && [ -s "$dir/g.vdb" ]'
printf 'G21 G90\nT5 M6\nG0 X5 Y5 Z5\nM2\n' > "$dir/l.ngc"
"$swarf" simulate "$dir/l.ngc" --stock box:0,0,-5,20,10,0 --tool T1=flat,D4 \
  --voxel 0.25 --out "$dir/l.vdb" > /dev/null 2> "$dir/stderr"
ok "linuxcnc: T5 not given stops at its T word (line 2)" '[ $? -eq 2 ] && grep -q "l.ngc:2:" "$dir/stderr"'

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
