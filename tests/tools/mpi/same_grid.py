#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""same_grid.py A.vdb B.vdb -- exit 0 when the two grids named "stock" are the
same voxel for voxel: same background and transform, same active topology,
same value at every active voxel and every inactive one a leaf stores
(max difference 0), read by pyopenvdb (an independent reader)."""
import sys

import numpy as np
import pyopenvdb as vdb


def load(path):
    g = vdb.read(path, "stock")
    return g


def dense(g, bbox):
    lo, hi = bbox
    shape = tuple(hi[k] - lo[k] + 1 for k in range(3))
    a = np.empty(shape, dtype=np.float32)
    g.copyToArray(a, ijk=lo)
    return a


def active_set(g):
    s = set()
    n = 0
    for it in g.citerOnValues():
        if it.count != 1:
            raise SystemExit("%s: an active tile (count %d): not a narrow band" % (g.name, it.count))
        s.add(it.min)
        n += 1
    return s


def main():
    a, b = load(sys.argv[1]), load(sys.argv[2])
    fails = []
    if a.background != b.background:
        fails.append("background %r vs %r" % (a.background, b.background))
    if a.transform.voxelSize() != b.transform.voxelSize():
        fails.append("voxel %r vs %r" % (a.transform.voxelSize(), b.transform.voxelSize()))
    sa, sb = active_set(a), active_set(b)
    if sa != sb:
        fails.append("active topology differs: %d vs %d active voxels, %d only in A, %d only in B"
                     % (len(sa), len(sb), len(sa - sb), len(sb - sa)))
    ba, bb = a.evalActiveVoxelBoundingBox(), b.evalActiveVoxelBoundingBox()
    lo = tuple(min(ba[0][k], bb[0][k]) - 8 for k in range(3))
    hi = tuple(max(ba[1][k], bb[1][k]) + 8 for k in range(3))
    da, db = dense(a, (lo, hi)), dense(b, (lo, hi))
    diff = float(np.max(np.abs(da.astype(np.float64) - db.astype(np.float64))))
    if diff != 0.0:
        fails.append("max |A - B| = %g over the active box and 8 voxels around" % diff)
    print("same_grid: %d active voxels, max difference %g, leaves %d / %d"
          % (len(sa), diff, a.leafCount(), b.leafCount()))
    if a.leafCount() != b.leafCount():
        fails.append("leaf count %d vs %d" % (a.leafCount(), b.leafCount()))
    for f in fails:
        print("FAIL: " + f)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
