#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# impeller_paths.sh -- one removal path against another on the first 600 lines
# of the LinuxCNC impeller (5-axis rotary sweeps, xyzac-trt, certified to
# 1e-6 mm): the program is milled once as swarf mills it and once with ENV=1,
# and every voxel of the two grids must agree within 1e-6 mm (inactive ones
# included), with the same active voxels (grids_match.py; pyopenvdb reads both).
#   impeller_paths.sh SWARF REAL_DIR VOXEL ENV WHAT [TOOL]
# Used by tools_rotary_blocks (ENV SWARF_REMOVE_FLAT: the removal's block
# hierarchy, stock/remove.cc, against the flat per-voxel path) and
# tools_rotary_range (ENV SWARF_REMOVE_PLAIN: the pruned rotary search,
# engine/sweep/sweep_rigid.c, against the full certified minimum at every voxel) and
# tools_rotary_ball (ENV SWARF_SWEEP_GENERAL: the ball end mill's path from the
# characteristic circles, engine/sweep/sweep_rigid_ball.c, against the general search;
# with TOOL a flat or bull end mill: its capsule's path there).
set -u
swarf=$1 real=$2 voxel=$3 env=$4 what=$5 tool=${6:-T1=ball,D4,L30}
if [ "${SWARF_REFERENCE_BUILT:-0}" != 1 ]; then
  echo "SKIPPED: this build has no reference paths; configure with -DSWARF_REFERENCE_PATHS=ON (tools/run test does)"
  exit 77
fi
[ -d "$real" ] || {
  echo "SKIPPED: the conformance corpus is not here ($real): it lives in ../shared beside a checkout"
  exit 77
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{ head -600 "$real/lcnc-impeller-7bl-xyzac.ngc"; echo M2; } > "$tmp/imp600.ngc"
opts=(--machine xyzac-trt --stock cylinder:z,42,0,30 --tool "$tool" --voxel "$voxel" --quiet)
"$swarf" simulate "$tmp/imp600.ngc" "${opts[@]}" --out "$tmp/default.vdb" 2> /dev/null || {
  echo "FAIL: the default run"; exit 1; }
env "$env=1" "$swarf" simulate "$tmp/imp600.ngc" "${opts[@]}" --out "$tmp/other.vdb" \
  2> /dev/null || { echo "FAIL: the run with $env=1"; exit 1; }
/usr/bin/python3 "$(dirname "$0")/grids_match.py" "$tmp/default.vdb" "$tmp/other.vdb" \
  "impeller 600 lines at $voxel mm, $what"
