#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# shape_fill.sh -- a new box or cylinder stock's band filled directly
# (stock/shape.cc) against the same band made by removing the shape's outside
# through the removal (SWARF_SHAPE_REMOVE=1, how it was built before): the
# grids must be bit-identical. A box whose faces lie off the voxel lattice and
# cylinders about each axis, at 0.3 mm, an empty program; pyopenvdb reads both.
#   shape_fill.sh SWARF
set -u
swarf=$1
if [ "${SWARF_REFERENCE_BUILT:-0}" != 1 ]; then
  echo "SKIPPED: this build has no reference paths; configure with -DSWARF_REFERENCE_PATHS=ON (tools/run test does)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'G21\nM2\n' > "$tmp/empty.ngc"
rc=0
n=0
for stock in box:-2.05,-1.3,-12.1,32,29,0.07 cylinder:z,12,-3,10.05 cylinder:x,7.3,-11,4 \
  cylinder:y,5,0.01,9; do
  n=$((n + 1))
  for how in fill remove; do
    env=0
    [ $how = remove ] && env=1
    SWARF_SHAPE_REMOVE=$env "$swarf" simulate "$tmp/empty.ngc" --stock "$stock" --voxel 0.3 \
      --tool T1=ball,D3,L20 --quiet --out "$tmp/$n-$how.vdb" 2> "$tmp/err" ||
      { echo "FAIL: $stock ($how): $(cat "$tmp/err")"; exit 1; }
  done
  /usr/bin/python3 "$(dirname "$0")/grids_match.py" "$tmp/$n-fill.vdb" "$tmp/$n-remove.vdb" \
    "$stock at 0.3 mm, filled against removed" --bits || rc=1
done
exit $rc
