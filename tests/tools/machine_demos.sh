#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# machine_demos.sh -- the demo programs of the xyzab-tdr, xyzbc-hh and xyzbc-ht
# machines end to end at a coarse voxel (fixtures/SOURCES.md says where each
# comes from), with the removed volume checked against what the program must
# remove.
#   machine_demos.sh SWARF FIXTURES
# - lcnc-xyzab-tdr-demo.ngc, LinuxCNC's own demo for its xyzab-tdr sim config.
#   HAL pins do not exist outside LinuxCNC: the test puts the config's values
#   (xyzab-tdr.xml's initval) in place of #<_hal[...]>, and T2 M6 in place of
#   M61 Q2 (swarf's parser has no M61). The tool tip stays at X >= 0 (the
#   rotary A table's face, G54 X0) and leans away from it (B 30..120: the tool
#   axis has X component sin B >= 1/2), so in TCP mode only the tilted flat
#   bottom (D3) can graze the face, at most 1.5 cos 30 = 1.3 mm deep: a disc
#   on the face loses a little, the same disc 2 mm below the face nothing. Read
#   as joint positions (mode=joint) the same program digs in.
# - xyzbc-hh-demo.ngc (TCP) and xyzbc-ht-demo.ngc (joint mode, the program
#   doing the kinematics itself, tool length from a tool table): 32 holes
#   drilled along the tilted tool axis, 4 mm wide and 5 mm deep along it:
#   32 pi 2^2 5 = 2010.62 mm^3 (an oblique cut of a cylinder has the volume of
#   its axis length), within 1 % (voxel 0.4).
set -u
swarf=$1 fx=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
removed() { # removed NAME PROGRAM ARGS...: prints the removed mm^3, or fails
  local name=$1 prog=$2; shift 2
  if ! "$swarf" simulate "$prog" --voxel 0.4 --out "$tmp/out.vdb" "$@" > "$tmp/summary" \
      2> "$tmp/err"; then
    echo "FAIL $name: $(cat "$tmp/err")" >&2; fail=1; echo -1; return
  fi
  sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$tmp/summary"
}
check() { # check NAME VALUE AWK-CONDITION(v)
  if awk -v v="$2" "BEGIN { exit !($3) }"; then echo "$1: $2 ($3)"; else
    echo "FAIL $1: $2 does not satisfy $3"; fail=1; fi
}

# xyzab-tdr: LinuxCNC's demo, HAL pins replaced by the sim config's values
sed -e 's/#<_hal\[xyzab_tdr_kins\.x-rot-point\]>/[-50]/g' \
    -e 's/#<_hal\[xyzab_tdr_kins\.y-rot-point\]>/[-50]/g' \
    -e 's/#<_hal\[xyzab_tdr_kins\.z-rot-point\]>/[-100]/g' \
    -e 's/#<_hal\[xyzab_tdr_kins\.x-offset\]>/[-20]/g' \
    -e 's/#<_hal\[xyzab_tdr_kins\.z-offset\]>/[-10]/g' \
    -e 's/^M61 Q2 /T2 M6 /' "$fx/lcnc-xyzab-tdr-demo.ngc" > "$tmp/tdr.ngc"
if grep -q '_hal\|M61' "$tmp/tdr.ngc"; then echo "FAIL: the demo changed upstream"; fail=1; fi
tdr=(--tool-table "$fx/lcnc-xyzab-tdr.tbl" --g54 -70,-50,-110)
v=$(removed "tdr face" "$tmp/tdr.ngc" --machine xyzab-tdr "${tdr[@]}" --stock cylinder:x,40,-20,0)
check "xyzab-tdr demo, TCP, disc on the face: removed mm^3" "$v" "v > 1 && v < 500"
v=$(removed "tdr below" "$tmp/tdr.ngc" --machine xyzab-tdr "${tdr[@]}" --stock cylinder:x,40,-20,-2)
check "xyzab-tdr demo, TCP, disc 2 mm below the face: removed mm^3" "$v" "v == 0"
v=$(removed "tdr joint" "$tmp/tdr.ngc" --machine xyzab-tdr,mode=joint "${tdr[@]}" \
    --stock cylinder:x,40,-20,-2)
check "xyzab-tdr demo read as joint positions: removed mm^3" "$v" "v > 1000"

# the head machines: 32 holes
holes=2010.62
v=$(removed "hh" "$fx/xyzbc-hh-demo.ngc" --machine xyzbc-hh --stock cylinder:z,50,-20,0 \
    --tool T1=flat,D4)
check "xyzbc-hh demo (TCP): removed mm^3 vs $holes" "$v" "v > 0.99 * $holes && v < 1.01 * $holes"
v=$(removed "ht" "$fx/xyzbc-ht-demo.ngc" --machine xyzbc-ht,mode=joint,head=80 \
    --tool-table "$fx/xyzbc-ht-demo.tbl" --stock cylinder:z,50,-20,0)
check "xyzbc-ht demo (joint): removed mm^3 vs $holes" "$v" "v > 0.99 * $holes && v < 1.01 * $holes"
# the head's pivot read from the tip instead of the gauge line misplaces the holes
v=$(removed "ht wrong head" "$fx/xyzbc-ht-demo.ngc" --machine xyzbc-ht,mode=joint,head=110 \
    --tool-table "$fx/xyzbc-ht-demo.tbl" --stock cylinder:z,50,-20,0)
check "xyzbc-ht demo with the tool length counted twice: removed mm^3" "$v" \
  "v < 0.9 * $holes || v > 1.1 * $holes"

# bad descriptions: exit 2, the flag named
for spec in xyzbc-hh,mode=joint xyzbc-hh,pivot=1,2,3 xyzab-tdr,head=5 xyzbc-ht,pivot=1; do
  "$swarf" simulate "$fx/xyzbc-hh-demo.ngc" --machine "$spec" --stock box:0,0,0,1,1,1 \
    --tool T1=flat,D4 --out "$tmp/o.vdb" 2> "$tmp/err"
  rc=$?
  if [ $rc -ne 2 ] || ! grep -q -- --machine "$tmp/err"; then
    echo "FAIL: --machine $spec gave rc=$rc: $(cat "$tmp/err")"; fail=1
  fi
done
# a program turning an axis the machine lacks: exit 2 at its line
printf 'G0 X0 Y0 Z5\nG0 A10\nM2\n' > "$tmp/a.ngc"
"$swarf" simulate "$tmp/a.ngc" --machine xyzbc-hh --stock box:0,0,0,1,1,1 --tool T1=flat,D4 \
  --out "$tmp/o.vdb" 2> "$tmp/err"
rc=$?
if [ $rc -ne 2 ] || ! grep -q "a.ngc:2:.*rotary axis the machine does not have" "$tmp/err"; then
  echo "FAIL: A on xyzbc-hh gave rc=$rc: $(cat "$tmp/err")"; fail=1
fi
exit $fail
