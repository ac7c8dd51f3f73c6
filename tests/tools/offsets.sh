#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# offsets.sh SWARF -- the simulator cuts where LinuxCNC's motion controller
# would put the tool tip: the same slot written plainly, with G43 H1 (the
# simulator's tool table has length offset 0 for every cutter: it follows the
# tip), shifted by a G10 L2 work offset or G92 and written back in program
# coordinates, or in inches, removes the same material (equal volume and the
# remaining grid: volume within 1e-6 mm^3, same active voxel count); a slot
# moved off the stock by a work offset removes nothing.
set -u
swarf=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0

# remaining PROGRAM-TEXT -> prints "VOLUME ACTIVE": the remaining grid's
# volume (mm^3, as `swarf info` reads it back) and its active voxel count.
remaining() {
  printf '%b\nM2\n' "$1" > "$dir/p.ngc"
  "$swarf" simulate "$dir/p.ngc" --stock box:0,0,-10,40,30,0 --tool T1=ball,D3,L12 \
    --voxel 0.25 --out "$dir/out.vdb" --quiet 2> "$dir/stderr" || { cat "$dir/stderr" >&2; echo fail; return; }
  "$swarf" info "$dir/out.vdb" | awk '/^volume/ { v = $2 } /^active_voxels/ { n = $2 }
    END { printf "%.3f %d\n", v, n }'
}
same() { # same NAME "VOLUME ACTIVE" "VOLUME ACTIVE"
  if awk -v a="$2" -v b="$3" 'BEGIN { split(a, x, " "); split(b, y, " ");
      exit !(x[1] > 1 && (x[1] - y[1]) ^ 2 < 1e-12 && x[2] == y[2]) }'; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1)); echo "FAIL $1: $2 vs $3"
  fi
}

untouched=$(remaining 'G0 Z5\nG0 X30\n')
plain=$(remaining 'G0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y12\nG0 Z5\n')
echo "untouched stock: $untouched, after the slot: $plain (mm^3, active voxels)"
if awk -v a="$untouched" -v b="$plain" 'BEGIN { split(a, x, " "); split(b, y, " "); exit !(x[1] - y[1] > 100) }'; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL the slot removes material"; fi
same "G43 H1" "$plain" "$(remaining 'T1 M6 G43 H1\nG0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y12\nG0 Z5\n')"
same "G10 L2 work offset" "$plain" "$(remaining 'G10 L2 P1 X3 Y-2 Z1\nG54\nG0 Z4\nG0 X2 Y12\nG1 Z-3 F100\nG1 X27 Y14\nG0 Z4\n')"
same "G55 offset" "$plain" "$(remaining 'G10 L2 P2 X10\nG55\nG0 Z5\nG0 X-5 Y10\nG1 Z-2 F100\nG1 X20 Y12\nG0 Z5\n')"
same "G92" "$plain" "$(remaining 'G0 X5 Y10 Z5\nG92 X0 Y0 Z0\nG1 Z-7 F100\nG1 X25 Y2\nG0 Z0\n')"
same "G20 inches" "$plain" "$(remaining 'G20\nG0 Z[5/25.4]\nG0 X[5/25.4] Y[10/25.4]\nG1 Z[-2/25.4] F4\nG1 X[30/25.4] Y[12/25.4]\nG0 Z[5/25.4]\n')"
same "parameters and a subroutine" "$plain" "$(remaining 'o100 sub\nG1 Z#1 F100\nG1 X#2 Y12\no100 endsub\n#<depth>=-2\nG0 Z5\nG0 X5 Y10\no100 call [#<depth>] [30]\nG0 Z5\nM2\n')"
same "a slot moved 100 mm off the stock by G10 L2 cuts nothing" "$untouched" \
  "$(remaining 'G10 L2 P1 X100\nG0 Z5\nG0 X5 Y10\nG1 Z-2 F100\nG1 X30 Y12\nG0 Z5\n')"

# swarf parse with simulate's setup: --g54 and --start list
# the moves in the workpiece frame simulate cuts in (G54's as set up), a G53
# move where the machine puts it; simulate with the same setup cuts there.
printf 'G21 G90\nG0 X5 Y5 Z5\nG1 Z-1 F100\nG1 X15\nG0 Z5\nG53 G0 X0 Y0\nM2\n' > "$dir/f.ngc"
setup=(--g54 10,20,-30 --start 0,0,40)
got=$("$swarf" parse "$dir/f.ngc" "${setup[@]}" 2> /dev/null | awk '{ printf "%s %s %s %s|", $1, $3, $4, $5 }')
want="2 5.0000 5.0000 5.0000|3 5.0000 5.0000 -1.0000|4 15.0000 5.0000 -1.0000|5 15.0000 5.0000 5.0000|6 -10.0000 -20.0000 5.0000|"
if [ "$got" = "$want" ]; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL parse --g54 --start: $got (want $want)"; fi
"$swarf" simulate "$dir/f.ngc" "${setup[@]}" --stock box:0,0,-10,40,30,0 --tool T1=flat,D4 \
  --voxel 0.25 --out "$dir/f.vdb" > "$dir/f.txt" 2> /dev/null
removed=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$dir/f.txt")
# the slot parse lists: 10 mm long, D4, 1 mm deep, from X5 Y5 (inside the stock)
if awk -v v="$removed" 'BEGIN { w = 10 * 4 * 1 + 3.14159265 * 4 * 1; exit !(v > 0.97 * w && v < 1.03 * w) }'; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL simulate with the same setup: removed $removed"; fi
bad=$("$swarf" parse "$dir/f.ngc" --g54 1,2 2>&1)
if [ $? -eq 2 ] && [[ "$bad" == *"--g54: give X,Y,Z"* ]]; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL parse --g54 1,2: $bad"; fi

# parse --tool-table (point 9): the table's G43 lengths, the moves listed at
# the tip of the tool in the spindle, where simulate cuts with the same table
# (without it parse used rs274's built-in T1 length, 0.7 in: Z 11.9794).
printf 'T1 P1 D4 Z+30 ;flat\nT2 P2 D6 Z+20\n' > "$dir/t.tbl"
printf 'G21 G90\nT1 M6\nG43 H1\nG0 X5 Y5 Z5\nG1 Z-1 F100\nG1 X15\nG0 Z5\nT2 M6\nG43 H2\nG0 Z20\nM2\n' > "$dir/t.ngc"
got=$("$swarf" parse "$dir/t.ngc" --tool-table "$dir/t.tbl" 2> /dev/null |
  awk '$2 != "TOOL" { printf "%s %s %s|", $1, $3, $5 }')
want="4 5.0000 5.0000|5 5.0000 -1.0000|6 15.0000 -1.0000|7 15.0000 5.0000|10 15.0000 20.0000|"
if [ "$got" = "$want" ]; then pass=$((pass + 1)); else
  fail=$((fail + 1)); echo "FAIL parse --tool-table: $got (want $want)"; fi
"$swarf" simulate "$dir/t.ngc" --tool-table "$dir/t.tbl" --stock box:0,0,-10,40,30,0 \
  --start 0,0,40 --voxel 0.25 --out "$dir/t.vdb" > "$dir/t.txt" 2> /dev/null
removed=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$dir/t.txt")
if awk -v v="$removed" 'BEGIN { w = 10 * 4 * 1 + 3.14159265 * 4 * 1; exit !(v > 0.97 * w && v < 1.03 * w) }'; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL simulate with the table: removed $removed"; fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
