#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# line_blocks.sh -- the removal's fast paths for 3-axis moves (stock/remove.cc:
# per-octant and per-cube summaries, a cube's cuts deepest first, the
# supporting planes of straight moves' convex sweeps, swarf_sweep_support)
# against the flat per-voxel path (SWARF_REMOVE_FLAT=1: every voxel the block
# centre cannot decide is evaluated), on two real CAM programs at 0.5 mm:
# 2,000 lines of camotics-tiger.nc's roughing (D2.5 flat end mill: slots,
# ramps, plunges; and the same with a D3 bull nose of corner radius 0.5, whose
# planes come from its core inside the sweep and from its torus around it)
# and the first 3,000 lines of camotics-bear.nc (1/8" ball).
# The grids must be bit-identical (the bounds keep a 1e-5 mm margin, so no
# voxel they pass over could change); pyopenvdb reads both.
#   line_blocks.sh SWARF REAL_DIR
set -u
swarf=$1 real=$2
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
{ head -1 "$real/camotics-tiger.nc"; echo F300; sed -n 17011,19010p "$real/camotics-tiger.nc"; echo M2; } \
  > "$tmp/tiger.nc"
{ head -3000 "$real/camotics-bear.nc"; echo M2; } > "$tmp/bear.nc"
cp "$tmp/tiger.nc" "$tmp/bull.nc"
declare -A opts=([tiger]="--stock box:-2,-1,-32,92,89,0 --tool T1=flat,D2.5,L20"
                 [bull]="--stock box:-2,-1,-32,92,89,0 --tool T1=bull,D3,R0.5,L20"
                 [bear]="--stock box:0,0,-20,80,80,0 --tool T1=ball,D3.175,L25")
for job in tiger bull bear; do
  # shellcheck disable=SC2086
  "$swarf" simulate "$tmp/$job.nc" ${opts[$job]} --voxel 0.5 --quiet --out "$tmp/$job-fast.vdb" \
    2> /dev/null || { echo "FAIL: $job, the run with the fast paths"; exit 1; }
  # shellcheck disable=SC2086
  SWARF_REMOVE_FLAT=1 "$swarf" simulate "$tmp/$job.nc" ${opts[$job]} --voxel 0.5 --quiet \
    --out "$tmp/$job-flat.vdb" 2> /dev/null || { echo "FAIL: $job, the flat run"; exit 1; }
done
rc=0
for job in tiger bull bear; do
  /usr/bin/python3 "$(dirname "$0")/grids_match.py" "$tmp/$job-fast.vdb" "$tmp/$job-flat.vdb" \
    "$job at 0.5 mm, the fast paths against the flat path" --bits || rc=1
done
exit $rc
