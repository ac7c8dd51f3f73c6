#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# assembly.sh SWARF SOURCE_DIR -- tool assemblies on the command line: the
# warnings of shank, holder and fixture collisions at their lines, the
# summary's counts, --fail-on collision (exit 4, outputs still written), tool
# tables and libraries (G43 lengths; bad files refused with FILE:LINE, exit 2,
# nothing written) and the options' own errors. The depths are those of
# test_collide (known in closed form); here the text is what is checked.
set -u
swarf=$1
src=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; fi; }
stock="--stock box:0,0,-40,60,40,0 --voxel 0.25 --units mm"

# holder 2 mm into the top (line 3) and the retract from there (line 4); a clamp
# on the top face that the cutter runs into (line 6) and leaves (line 7)
printf 'G0 X20 Y20 Z5\nG1 Z-20 F300\nG1 Z-27\nG0 Z30\nG0 X30 Y20 Z2\nG1 X58\nG0 Z30\nM2\n' > "$dir/p.ngc"
run() { "$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6,L10,S25 --holder T1=20x40 \
  --fixture box:50,0,0,60,40,5 --out "$dir/out.vdb" "$@" > "$dir/summary" 2> "$dir/stderr"; }
run
rc=$?
cat "$dir/summary" "$dir/stderr"
ok "collisions are warnings: exit 0" '[ $rc -eq 0 ] && [ -s "$dir/out.vdb" ]'
ok "holder warnings at lines 3 and 4, 2.0 mm deep" \
  '[ "$(grep -c "p.ngc:[34]:[0-9]*: warning: holder of T1 hits the material (2.0 mm deep)" "$dir/stderr")" = 2 ]'
ok "fixture warnings at lines 6 and 7" \
  '[ "$(grep -c "p.ngc:[67]:[0-9]*: warning: T1 cutter hits fixture 1 (3.0 mm deep)" "$dir/stderr")" = 2 ]'
ok "no shank warning (the shank follows the flutes into their hole)" '! grep -q shank "$dir/stderr"'
ok "the summary counts them" 'grep -q "alarms 4 (0 rapid moves cutting into material, 0 moves gouging the design, 4 collisions: 0 shank, 2 holder, 2 fixture)" "$dir/summary"'
rm -f "$dir/out.vdb"
run --fail-on collision
rc=$?
ok "--fail-on collision: exit 4, outputs written" '[ $rc -eq 4 ] && [ -s "$dir/out.vdb" ]'

# the same clamp as a closed STL mesh (12 triangles, outward normals): the same warnings
/usr/bin/python3 - "$dir/clamp.stl" <<'PY'
import sys
lo, hi = (50, 0, 0), (60, 40, 5)
c = lambda i: tuple(hi[k] if (i >> k) & 1 else lo[k] for k in range(3))
faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
with open(sys.argv[1], "w") as f:
    f.write("solid clamp\n")
    for a, b, cc, d in faces:
        for t in ((a, b, cc), (a, cc, d)):
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for i in t:
                f.write("   vertex %g %g %g\n" % c(i))
            f.write("  endloop\n endfacet\n")
    f.write("endsolid clamp\n")
PY
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6,L10,S25 --holder T1=20x40 \
  --fixture "stl:$dir/clamp.stl" --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
rc=$?
ok "an STL fixture: exit 0, fixture warnings at lines 6 and 7, 3.0 mm deep" \
  '[ $rc -eq 0 ] && [ "$(grep -c "p.ngc:[67]:[0-9]*: warning: T1 cutter hits fixture 1 (3.0 mm deep)" "$dir/stderr")" = 2 ]'
printf 'solid open\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid open\n' > "$dir/open.stl"
rm -f "$dir/out.vdb"
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6 --fixture "stl:$dir/open.stl" \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
rc=$?
ok "an open STL fixture is refused: exit 2, nothing written" \
  '[ $rc -eq 2 ] && [ ! -e "$dir/out.vdb" ] && grep -q "fixture 1" "$dir/stderr"'

printf 'G0 X10 Y10 Z5\nG1 Z-9.5 F300\nG1 X50\nG1 Y30 Z-9\nG0 Z30\nM2\n' > "$dir/clean.ngc"
"$swarf" simulate "$dir/clean.ngc" $stock --tool T1=flat,D6,L10,S25 --holder T1=20x40 \
  --out "$dir/out.vdb" --fail-on collision > "$dir/summary" 2> "$dir/stderr"
ok "within the flute length: no warning, exit 0" '[ $? -eq 0 ] && ! grep -q warning "$dir/stderr"'

# a table in inches (T1 is 2" long, 0.25" wide) and G43: the tip where the program says
printf 'T1 P1 D0.25 Z+2.0 ;quarter inch end mill\n' > "$dir/t.tbl"
printf 'T1 M6\nG43 H1\nG0 X10 Y10 Z5\nG1 Z-3 F100\nG0 Z30\nM2\n' > "$dir/g43.ngc"
"$swarf" simulate "$dir/g43.ngc" $stock --tool-table "$dir/t.tbl" --tool-table-units in \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
removed=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$dir/summary")
ok "G43 H1 with the table's length: a 6.35 mm hole 3 deep (95.0 mm^3), got $removed" \
  'awk -v r="$removed" "BEGIN { exit !(r > 93 && r < 97) }"'
# --tool overrides the table's shape, keeps its length
"$swarf" simulate "$dir/g43.ngc" $stock --tool-table "$dir/t.tbl" --tool-table-units in \
  --tool T1=flat,D4 --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
removed=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$dir/summary")
ok "--tool T1=flat,D4 over the table: a 4 mm hole 3 deep (37.7 mm^3), got $removed" \
  'awk -v r="$removed" "BEGIN { exit !(r > 36.5 && r < 39) }"'
# a library: T1 (85.5 long, holder D20 at S30) plunged to Z-32 under G43 H1: the
# holder's face 2 mm into the top
printf 'T1 M6\nG43 H1\nG0 X20 Y20 Z5\nG1 Z-32 F300\nG1 Z40\nM2\n' > "$dir/lib.ngc"
"$swarf" simulate "$dir/lib.ngc" $stock --tool-library "$src/tooltables/library.json" \
  --out "$dir/out.vdb" > "$dir/summary" 2> "$dir/stderr"
cat "$dir/stderr"
ok "a library's assembly: its holder hits at line 4, 2.0 mm deep" \
  'grep -q "lib.ngc:4:[0-9]*: warning: holder of T1 hits the material (2.0 mm deep)" "$dir/stderr"'

# bad inputs: FILE:LINE, exit 2, nothing written
rm -f "$dir/out.vdb"
printf 'T1 P1 D6 Z+30\nT2 P2 D6 K3\n' > "$dir/bad.tbl"
"$swarf" simulate "$dir/p.ngc" $stock --tool-table "$dir/bad.tbl" --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
rc=$?
cat "$dir/stderr"
ok "a bad table: FILE:LINE, exit 2, nothing written" \
  '[ $rc -eq 2 ] && grep -q "^$dir/bad.tbl:2: unknown word \"K3\"" "$dir/stderr" && [ ! -e "$dir/out.vdb" ]'
printf '{"tools": [\n  {"number": 1,\n   "cutter": "flat,D6",\n   "stickout": "long"}\n]}\n' > "$dir/bad.json"
"$swarf" simulate "$dir/p.ngc" $stock --tool-library "$dir/bad.json" --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
rc=$?
cat "$dir/stderr"
ok "a bad library: FILE:LINE, exit 2, nothing written" \
  '[ $rc -eq 2 ] && grep -q "^$dir/bad.json:4: \"stickout\" must be a number" "$dir/stderr" && [ ! -e "$dir/out.vdb" ]'
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6 --holder T1=20x40 --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "a holder without a stick-out is refused" '[ $? -eq 2 ] && grep -q "no stick-out" "$dir/stderr"'
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6,S25 --holder T1=20x0 --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "--holder with a zero height is refused" '[ $? -eq 2 ] && grep -q "^swarf simulate: --holder:" "$dir/stderr"'
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6,S25 --holder T2=20x40 --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "--holder of a tool not given is refused" '[ $? -eq 2 ] && grep -q "T2 is not a tool" "$dir/stderr"'
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6,S-3 --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "a negative stick-out is refused" '[ $? -eq 2 ] && grep -q "bad S or N" "$dir/stderr"'
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6 --fixture box:1,2,3 --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "a bad --fixture is refused" '[ $? -eq 2 ] && grep -q -- "--fixture: bad number" "$dir/stderr"'
"$swarf" simulate "$dir/p.ngc" $stock --tool T1=flat,D6 --fail-on everything --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "--fail-on takes collision only" '[ $? -eq 2 ]'
"$swarf" simulate "$dir/p.ngc" $stock --tool-table /nonexistent.tbl --out "$dir/out.vdb" \
  > /dev/null 2> "$dir/stderr"
ok "a missing table is refused" '[ $? -eq 2 ] && grep -q "cannot open the tool table" "$dir/stderr"'
ok "nothing written by the refusals" '[ ! -e "$dir/out.vdb" ]'
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
