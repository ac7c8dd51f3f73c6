#!/usr/bin/env bash
# rotary_blocks.sh -- the removal's block hierarchy (stock/remove.cc: block,
# octant and cube centres decide for the voxels below them) against the flat
# per-voxel path (SWARF_REMOVE_FLAT=1: every voxel the block centre cannot
# decide is evaluated), on the first 600 lines of the LinuxCNC impeller
# (5-axis rotary sweeps, certified to 1e-6 mm) at a coarse voxel: the two grids
# must agree voxel for voxel to 1e-6 mm (the hierarchy's margins make them
# bit-identical; pyopenvdb reads both).
#   rotary_blocks.sh SWARF REAL_DIR
set -u
swarf=$1 real=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
head -600 "$real/lcnc-impeller-7bl-xyzac.ngc" > "$tmp/imp600.ngc"
opts=(--machine xyzac-trt --stock cylinder:z,42,0,30 --tool T1=ball,D4,L30 --voxel 0.5 --quiet)
"$swarf" simulate "$tmp/imp600.ngc" "${opts[@]}" --out "$tmp/blocks.vdb" 2> /dev/null || {
  echo "FAIL: the run with the hierarchy"; exit 1; }
SWARF_REMOVE_FLAT=1 "$swarf" simulate "$tmp/imp600.ngc" "${opts[@]}" --out "$tmp/flat.vdb" \
  2> /dev/null || { echo "FAIL: the flat run"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/grids_match.py" "$tmp/blocks.vdb" "$tmp/flat.vdb" \
  "impeller 600 lines at 0.5 mm, the hierarchy against the flat path"
