#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""faces.py SWARF -- cuts that end exactly on a stock face are exact: a box's
faces on the lattice hold 0 at their voxel centres, and a cut through them
used to leave a sheet of no thickness counted as half a voxel (4948.8 instead
of 5000 mm^3 for the slot below at 0.2 mm).

- slot: a D10 flat end mill along Y20 from X-10 to X60 through a 50 x 40 x
  10 mm box: 5000 mm^3 within 0.2 % for every depth at or below Z-10, at
  0.2 mm (faces on the lattice) and 0.16 mm (off it); to Z-9.9 the 0.1 mm
  floor left stays (4950 mm^3).
- through-bore: a D10 plunge through the box at 0.2 and 0.16 mm removes
  pi 25 10 mm^3 within 0.5 %, and no material is left in the bore at the
  bottom face (pyopenvdb: the voxel at its centre is air).
- stock to leave: a profile 0.5 mm around an island design, cut through
  the box: the excess is the same at 0.2, 0.16 and 0.1 mm within 0.2 % (the
  sheets, 60 mm^3 at 0.2 mm, made it 0.6 % more there).
"""
import math
import os
import sys

import pyopenvdb as vdb

import verifykit as vk

swarf = sys.argv[1]
d = vk.workdir()
BOX = "box:0,0,-10,50,40,0"


def run(program, voxel, extra=(), tool="T1=flat,D10,L30"):
    return vk.Run(swarf, program, ["--stock", BOX, "--tool", tool, "--voxel", str(voxel)] +
                  list(extra), d, report=False)


def removed(r):
    for l in r.stdout.splitlines():
        if "removed" in l and "mm^3" in l:
            return float(l.split("removed")[1].split("mm^3")[0])
    return None


for voxel in (0.2, 0.16):
    for z in (-10, -10.1, -10.5, -9.9):
        r = run("G21 G90\nG0 Z5\nG0 X-10 Y20\nG1 Z%g F300\nG1 X60\nG0 Z5\nM2\n" % z, voxel)
        want = 50 * 10 * min(10, -z)
        got = removed(r)
        vk.check(r.status == 0 and got is not None and abs(got - want) <= 0.002 * want,
                 "slot to Z%g at %g mm: removed %s mm^3, %g within 0.2 %%" % (z, voxel, got, want))

bore = math.pi * 25 * 10
for voxel in (0.2, 0.16):
    r = run("G21 G90\nG0 Z5\nG0 X25 Y20\nG1 Z-10 F100\nG0 Z5\nM2\n", voxel)
    got = removed(r)
    vk.check(r.status == 0 and got is not None and abs(got - bore) <= 0.005 * bore,
             "through-bore at %g mm: removed %s mm^3, pi 25 10 = %.2f within 0.5 %%" % (voxel, got, bore))
    if r.status == 0:
        g = vdb.read(r.out, "stock")
        ijk = tuple(int(round(c / voxel)) for c in (25, 20, -10))
        v = g.getConstAccessor().getValue(ijk)
        vk.check(v > 0, "through-bore at %g mm: no disc at the bottom face (value %g at its centre)" %
                 (voxel, v))

design = os.path.join(d, "island.stl")
vk.write_stl(design, vk.box_triangles((15, 12, -10), (35, 28, 0)))
# the D6 tool's centre 3.5 mm off the island: 0.5 mm of stock left on its sides
profile = ("G21 G90\nG0 Z5\nG0 X11.5 Y8.5\nG1 Z-10 F200\nG1 X38.5\nG1 Y31.5\nG1 X11.5\n"
           "G1 Y8.5\nG0 Z5\nM2\n")
excess = {}
for voxel in (0.2, 0.16, 0.1):
    r = vk.Run(swarf, profile, ["--stock", BOX, "--tool", "T1=flat,D6,L30", "--voxel", str(voxel),
                                "--design", design, "--tolerance", "0.1"], d)
    if vk.check(r.status == 0 and r.report is not None, "profile at %g mm: %s" % (voxel, r.stderr[-300:])):
        excess[voxel] = r.report["summary"]["design"]["excess_mm3"]
print("excess by voxel:", excess)
if len(excess) == 3:
    lo, hi = min(excess.values()), max(excess.values())
    vk.check(hi - lo <= 0.002 * hi, "the excess does not depend on the faces' place on the lattice "
             "(%.1f..%.1f mm^3)" % (lo, hi))
sys.exit(vk.done())
