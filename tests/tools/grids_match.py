#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""grids_match.py A.vdb B.vdb LABEL [--bits] -- two runs of one program give
the same stock: the same number of active voxels (more than 10,000, so the
runs did cut) and, over the union of their active boxes, values within
1e-6 mm (--bits: bit-identical). Read with pyopenvdb and numpy, not swarf.
Used by impeller_paths.sh (tools_rotary_blocks, _range, _ball) and line_blocks.sh to hold a fast
removal path to its reference path. Exit 0 when they match."""
import sys

import numpy as np
import pyopenvdb as vdb


def main(argv):
    a, b = (vdb.read(f, "stock") for f in argv[1:3])
    label, bits = argv[3], "--bits" in argv[4:]
    na, nb = a.activeVoxelCount(), b.activeVoxelCount()
    (alo, ahi), (blo, bhi) = a.evalActiveVoxelBoundingBox(), b.evalActiveVoxelBoundingBox()
    lo = [min(x, y) for x, y in zip(alo, blo)]
    hi = [max(x, y) for x, y in zip(ahi, bhi)]
    shape = tuple(h - l + 1 for l, h in zip(lo, hi))
    A, B = np.zeros(shape, np.float32), np.zeros(shape, np.float32)
    a.copyToArray(A, ijk=lo)
    b.copyToArray(B, ijk=lo)
    d = float(np.abs(A.astype(np.float64) - B).max())
    changed = int((A.view(np.uint32) != B.view(np.uint32)).sum())
    ok = na == nb and na > 10000 and (changed == 0 if bits else d <= 1e-6)
    print(f"{label}: {na} vs {nb} active voxels, {changed} voxels differ, "
          f"max |difference| {d:.3g} mm: {'ok' if ok else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
