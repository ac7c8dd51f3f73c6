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
/usr/bin/python3 - "$tmp/pruned.vdb" "$tmp/plain.vdb" "$voxel" <<'PY'
import sys
import numpy as np
import pyopenvdb as vdb
a, b = (vdb.read(f, "stock") for f in sys.argv[1:3])
na, nb = a.activeVoxelCount(), b.activeVoxelCount()
lo = [min(x, y) for x, y in zip(a.evalActiveVoxelBoundingBox()[0], b.evalActiveVoxelBoundingBox()[0])]
hi = [max(x, y) for x, y in zip(a.evalActiveVoxelBoundingBox()[1], b.evalActiveVoxelBoundingBox()[1])]
shape = tuple(h - l + 1 for l, h in zip(lo, hi))
A, B = np.zeros(shape, np.float32), np.zeros(shape, np.float32)
a.copyToArray(A, ijk=lo)
b.copyToArray(B, ijk=lo)
D = np.abs(A.astype(np.float64) - B)
d = float(D.max())
changed = int((A != B).sum())
print(f"impeller 600 lines at {sys.argv[3]} mm: {na} vs {nb} active voxels, "
      f"{changed} voxels differ, max |difference| {d:.3g} mm")
ok = na == nb and na > 10000 and d <= 1e-6
print("ok" if ok else "FAIL: the pruned path's grid differs from the plain certified path's")
sys.exit(0 if ok else 1)
PY
