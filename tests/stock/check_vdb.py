#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""check_vdb.py -- cross-check a .vdb written by swarf with pyopenvdb.

Usage: /usr/bin/python3 check_vdb.py FILE.vdb
Reads FILE.vdb.txt (written by test_stock_io): "stock VOXEL HALF_WIDTH ACTIVE"
then lines "I J K VALUE" (index coordinates and the stored value). Checks the
grid name, class, voxel size, background, active voxel count and values.
Exit status 0 if all agree.
"""
import sys

import pyopenvdb as vdb


def main(path):
    with open(path + ".txt") as f:
        name, voxel, half_width, active = f.readline().split()
        voxel, half_width, active = float(voxel), int(half_width), int(active)
        samples = [line.split() for line in f if line.strip()]
    failures = []

    def check(cond, what):
        print(("ok   " if cond else "FAIL ") + what)
        if not cond:
            failures.append(what)

    names = [g.name for g in vdb.readAllGridMetadata(path)]
    check(names == [name], "grids in file: %s" % names)
    grid = vdb.read(path, name)
    check(grid.gridClass == vdb.GridClass.LEVEL_SET, "class %s" % grid.gridClass)
    vs = grid.transform.voxelSize()
    check(all(abs(v - voxel) <= 1e-12 * voxel for v in vs), "voxel size %s vs %g" % (vs, voxel))
    check(abs(grid.background - half_width * voxel) <= 1e-6, "background %g" % grid.background)
    check(grid.activeVoxelCount() == active, "active voxels %d vs %d" % (grid.activeVoxelCount(), active))
    acc = grid.getConstAccessor()
    for i, j, k, value in samples:
        got = acc.getValue((int(i), int(j), int(k)))
        check(abs(got - float(value)) <= 1e-7, "value at (%s,%s,%s): %.9g vs %s" % (i, j, k, got, value))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
