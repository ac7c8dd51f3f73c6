#!/usr/bin/env bash
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

printf 'G21 G0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y10\nG0 X35\nG0 Z5\nG0 X5 Y20\nG0 Z-1\nG0 X20\nG0 Z5\nG0 X10 Y10\nG0 Z-2\nG0 X25\nG0 Z5\n' > "$dir/p.ngc"
"$swarf" simulate "$dir/p.ngc" --stock box:0,0,-10,40,30,0 --tool T1=ball,D3,L12 --voxel 0.25 \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
rc=$?
cat "$dir/summary" "$dir/stderr"
ok "exits 0 (alarms are warnings)" '[ $rc -eq 0 ] && [ -s "$dir/out.vdb" ]'
ok "three alarms in the summary" 'grep -q "alarms 3 " "$dir/summary"'
ok "the lines of the alarms" '[ "$(grep -o "p.ngc:[0-9]*:[0-9]*: warning: rapid" "$dir/stderr" | cut -d: -f2 | tr "\n" " ")" = "5 8 9 " ]'

printf 'G21 G0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y10\nG0 Z5\nG0 X0 Y0\n' > "$dir/clean.ngc"
"$swarf" simulate "$dir/clean.ngc" --stock box:0,0,-10,40,30,0 --tool T1=ball,D3,L12 --voxel 0.25 \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
ok "a clean program has no alarm" 'grep -q "alarms 0 " "$dir/summary" && ! grep -q warning "$dir/stderr"'
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
