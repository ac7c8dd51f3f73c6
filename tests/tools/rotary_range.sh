#!/usr/bin/env bash
# rotary_range.sh -- the pruned rotary sweep (issue 12: each voxel's search over
# the move resolves only the values that change the voxel, the block's cuts
# taken deepest first; stock/remove.cc, engine/sweep_rigid.c) against the
# previous certified path (SWARF_REMOVE_PLAIN=1: the full certified minimum at
# every voxel asked, cuts in batch order) on the first 600 lines of the LinuxCNC
# impeller (5-axis, xyzac-trt): every voxel of the two grids within 1e-6 mm
# (inactive ones included), and the same active voxels. pyopenvdb reads both.
#   rotary_range.sh SWARF REAL_DIR [VOXEL]
set -u
swarf=$1 real=$2 voxel=${3:-0.4}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
head -600 "$real/lcnc-impeller-7bl-xyzac.ngc" > "$tmp/imp600.ngc"
opts=(--machine xyzac-trt --stock cylinder:z,42,0,30 --tool T1=ball,D4,L30 --voxel "$voxel" --quiet)
"$swarf" simulate "$tmp/imp600.ngc" "${opts[@]}" --out "$tmp/pruned.vdb" 2> /dev/null || {
  echo "FAIL: the pruned run"; exit 1; }
SWARF_REMOVE_PLAIN=1 "$swarf" simulate "$tmp/imp600.ngc" "${opts[@]}" --out "$tmp/plain.vdb" \
  2> /dev/null || { echo "FAIL: the plain run"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/grids_match.py" "$tmp/pruned.vdb" "$tmp/plain.vdb" \
  "impeller 600 lines at $voxel mm, the pruned path against the plain certified one"
