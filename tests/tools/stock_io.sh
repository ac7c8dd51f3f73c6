#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# stock_io.sh SWARF PYTHON SOURCE_DIR -- stocks from files and the next setup,
# end to end on the command line, read back by an independent
# reader (stock_check.py: pyopenvdb, numpy):
#  - an STL box stock (written by the test) = the box stock, voxel by voxel;
#  - a .vdb stock: run A, then program B on A's output = one run of A + B
#    (1e-6 mm), also when another tool wrote it (the first float level set,
#    not named "stock", after a fog volume);
#  - a second setup: A's output flipped (rx=180,tz=-10): the slot is on the
#    bottom face, the volume is the box less the slot (analytic);
#  - swarf info calls every output valid at voxel sizes that rounded badly
#    in float (0.3 mm);
#  - a design 1 mm off (beyond its 2-voxel band): the PLY's deviations and
#    swarf compare measure it exactly; an unknown mesh extension is refused;
#  - bad input: open, non-manifold and empty STLs, a .vdb without a level
#    set, a bad transform: exit 2, a message, nothing written.
set -u
swarf=$1
py=$2
src=$3
check="$py $src/stock_check.py"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; fi; }
sim() { "$swarf" simulate "$@" --units mm > "$dir/summary" 2> "$dir/stderr"; }

A='G0 Z5\nG0 X5 Y10\nG1 Z-2 F300\nG1 X35 F600\nG0 Z5\n'
B='G0 Z5\nG0 X20 Y3\nG1 Z-1 F300\nG1 Y17 F600\nG0 Z5\n'
printf "${A}M2\n" > "$dir/a.ngc"
printf "${B}M2\n" > "$dir/b.ngc"
printf "${A}${B}M2\n" > "$dir/ab.ngc"
box=box:0,0,-10,40,20,0
tool="--tool T1=flat,D6,L12"

# STL stock = box stock
$check box-stl "$dir/box.stl" 0,0,-10,40,20,0 good
sim "$dir/a.ngc" --stock "stl:$dir/box.stl" $tool --out "$dir/stl.vdb"
ok "STL stock runs" '[ $? -eq 0 ] && [ -s "$dir/stl.vdb" ]'
sim "$dir/a.ngc" --stock $box $tool --out "$dir/a.vdb"
ok "box stock runs" '[ $? -eq 0 ] && [ -s "$dir/a.vdb" ]'
ok "STL stock = box stock (0.002 mm = 0.01 voxel)" '$check same "$dir/stl.vdb" "$dir/a.vdb" 0.002'

# .vdb stock: A then B = A + B
sim "$dir/b.ngc" --stock "vdb:$dir/a.vdb" $tool --out "$dir/a_b.vdb"
ok "B on A's output runs" '[ $? -eq 0 ] && [ -s "$dir/a_b.vdb" ]'
sim "$dir/ab.ngc" --stock $box $tool --out "$dir/ab.vdb"
ok "A then B = one run of A + B (1e-6 mm)" '$check same "$dir/a_b.vdb" "$dir/ab.vdb" 1e-6'
# another tool's .vdb: the first float level set (here "part", after a fog
# volume) is the stock
$check other-vdb "$dir/a.vdb" "$dir/other.vdb"
sim "$dir/b.ngc" --stock "vdb:$dir/other.vdb" $tool --out "$dir/o_b.vdb"
ok "B on another tool's .vdb (level set \"part\" after a fog volume) = A + B" \
  '[ -s "$dir/o_b.vdb" ] && $check same "$dir/o_b.vdb" "$dir/ab.vdb" 1e-6'

# second setup: flipped about X and lowered 10: the slot (y 7..13, z -2..0)
# is now at y -13..-7, z -10..-8; a face pass of B at the new top cuts 1 mm
sim "$dir/b.ngc" --stock "vdb:$dir/a.vdb" --stock-transform rx=180,tz=-10 $tool --out "$dir/flip.vdb"
ok "the flipped setup runs" '[ $? -eq 0 ]'
ok "the slot is on the bottom face, the top is whole" \
  '$check sample "$dir/flip.vdb" 20,-10,-9:+ 20,-10,-7:- 10,-10,-0.5:- 20,-18,-9.5:-'
# box 8000, slot 2 (30 x 6 + 9 pi) (A), B's groove in the flipped part: the
# stock now spans y -20..0: B's line at x 20 from y 3 to 17 stays above it
ok "its volume: the box less A's slot" \
  '$check volume "$dir/flip.vdb" $(awk "BEGIN { print 8000 - 2 * (180 + 9 * 3.14159265358979) }") 8'

# swarf info at voxel sizes that rounded badly (0.3) and others
for v in 0.3 0.15 0.35 0.7 1.1; do
  sim "$dir/a.ngc" --stock $box $tool --voxel $v --out "$dir/v.vdb"
  ok "swarf info: a ${v} mm output is a valid level set" \
    '"$swarf" info "$dir/v.vdb" | grep -q "level_set valid"'
done
sim "$dir/a.ngc" --stock "stl:$dir/box.stl" $tool --voxel 0.3 --out "$dir/v.vdb"
ok "swarf info: an STL stock's 0.3 mm output is valid" '"$swarf" info "$dir/v.vdb" | grep -q "level_set valid"'
sim "$dir/b.ngc" --stock "vdb:$dir/a.vdb" $tool --voxel 0.3 --out "$dir/v.vdb"
ok "swarf info: a resampled stock's 0.3 mm output is valid" '"$swarf" info "$dir/v.vdb" | grep -q "level_set valid"'

# a design 1 mm below the top (beyond the 2-voxel band): the PLY's deviation there is
# 1.0 (measured on the design's triangles beyond its band); swarf compare
# gives the same largest excess and deepest gouge (the slot is 1 mm deep in
# it); a mesh of unknown extension is refused before the run
$check box-stl "$dir/design.stl" 0,0,-10,40,20,-1 good
sim "$dir/a.ngc" --stock $box $tool --design "$dir/design.stl" --out "$dir/d.vdb" --mesh "$dir/d.ply"
ok "a run with a design and a PLY" '[ $? -eq 0 ] && [ -s "$dir/d.ply" ]'
ok "the PLY's deviation at the top is 1.0 mm" '$check ply-dev "$dir/d.ply" 0 1.0 0.01'
"$swarf" compare "$dir/d.vdb" "$dir/design.stl" > "$dir/cmp" 2>&1
ok "swarf compare: largest excess 1.0, deepest gouge 1.0" \
  'grep -q "^excess_mm=1.0000" "$dir/cmp" && grep -q "^gouge_depth_mm=1.0000" "$dir/cmp"'
rm -f "$dir/out.vdb"
sim "$dir/a.ngc" --stock $box $tool --out "$dir/out.vdb" --mesh "$dir/out.xyz"
rc=$?
ok "--mesh .xyz: exit 2, nothing written" '[ $rc -eq 2 ] && [ ! -e "$dir/out.vdb" ] && [ ! -e "$dir/out.xyz" ]'

# bad input: exit 2, a message naming the file, nothing written
for damage in open nonmanifold empty; do
  $check box-stl "$dir/bad.stl" 0,0,-10,40,20,0 $damage
  rm -f "$dir/out.vdb"
  sim "$dir/a.ngc" --stock "stl:$dir/bad.stl" $tool --out "$dir/out.vdb"
  rc=$?
  ok "$damage STL: exit 2, named, nothing written" \
    '[ $rc -eq 2 ] && grep -q "bad.stl" "$dir/stderr" && [ ! -e "$dir/out.vdb" ]'
done
$check fog-vdb "$dir/fog.vdb"
sim "$dir/a.ngc" --stock "vdb:$dir/fog.vdb" $tool --out "$dir/out.vdb"
rc=$?
ok "a .vdb without a level set: exit 2, nothing written" \
  '[ $rc -eq 2 ] && grep -q "fog.vdb" "$dir/stderr" && [ ! -e "$dir/out.vdb" ]'
for t in rx=abc tq=3 rx=1,rx=2 tx=; do
  sim "$dir/a.ngc" --stock "vdb:$dir/a.vdb" --stock-transform "$t" $tool --out "$dir/out.vdb"
  rc=$?
  ok "--stock-transform $t: exit 2, nothing written" \
    '[ $rc -eq 2 ] && grep -q -- "--stock-transform" "$dir/stderr" && [ ! -e "$dir/out.vdb" ]'
done
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
