#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# rotary_demos.sh -- the LinuxCNC 5-axis demos and the UGS 4th-axis wrap end to
# end at a coarse voxel, plus the rotary options' error messages.
#   rotary_demos.sh SWARF REAL_DIR
# The files run as they are: M428/M429 (LinuxCNC's switch to and from
# tool-centre-point kinematics) make no motion, --machine selects the mode.
set -u
swarf=$1 real=$2
[ -d "$real" ] || {
  echo "SKIPPED: the conformance corpus is not here ($real): it lives in ../shared beside a checkout"
  exit 77
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
run() { # run NAME MACHINE STOCK TOOL: simulate the file, check removal
  local name=$1
  if ! "$swarf" simulate "$real/$name" --machine "$2" --stock "$3" --tool "$4" --voxel 0.8 \
      --out "$tmp/out.vdb" > "$tmp/summary" 2> "$tmp/err"; then
    echo "FAIL $name: $(cat "$tmp/err")"; fail=1; return
  fi
  local pct
  pct=$(sed -n 's/.*removed [0-9.]* mm^3 (\([0-9.]*\)%).*/\1/p' "$tmp/summary")
  echo "$name: removed $pct% of the stock"
  awk -v p="$pct" 'BEGIN { exit !(p > 1 && p < 95) }' || { echo "FAIL $name: removed $pct%"; fail=1; }
}
run lcnc-impeller-7bl-xyzac.ngc xyzac-trt cylinder:z,42,0,30 T1=ball,D4,L30
run lcnc-boat-xyzac.ngc xyzac-trt box:-50,-27,-13.25,47,24,0 T1=flat,D10,L30
run lcnc-boat-xyzbc.ngc xyzbc-trt box:-50,-27,-13.25,47,24,0 T1=flat,D10,L30
run ugs-rotation.ngc xyza cylinder:x,25,0,81 T1=ball,D3.175,L20
bad() { # bad FLAG-TEXT ARGS...: exit 2 and the flag named on stderr
  local want=$1; shift
  "$swarf" simulate "$real/ugs-rotation.ngc" --tool T1=ball,D3 --out "$tmp/o.vdb" "$@" 2> "$tmp/err"
  local rc=$?
  if [ $rc -ne 2 ] || ! grep -q -- "$want" "$tmp/err"; then
    echo "FAIL: $* gave rc=$rc: $(cat "$tmp/err")"; fail=1
  fi
}
bad --machine --stock box:0,0,0,1,1,1 --machine xyzq
bad --machine --stock box:0,0,0,1,1,1 --machine xyza,pivot=1
bad --stock --stock cylinder:w,5,0,1
bad --stock --stock cylinder:x,-5,0,1
bad --stock --stock cylinder:x,5,2,1
bad "rotary axis the machine does not have" --stock cylinder:x,25,0,81
exit $fail
