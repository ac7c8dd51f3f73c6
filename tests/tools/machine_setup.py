#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""machine_setup.py SWARF -- the machine's setup in `swarf simulate`:

- start position: a program whose origin is inside the stock (CAMotics
  #454's reproduction: stock -5,-5,0..125,65,6, the only motion a retract)
  cuts nothing before its first move by default (the grid read with pyopenvdb
  keeps the whole box's volume and material at the origin), and the summary
  says where it started;
  --start 0,0,0 reproduces the phantom cut (pi r^2 h removed);
- G53 with work offsets: `G53 G0 Z-3` with G54's Z at -50 (--g54 or
  --offsets FILE) stays in the air; the same program with no offsets plunges
  (a rapid alarm and material removed); the slot cut through G54 lands where
  the offset puts it (same volume as the plain slot at the shifted place);
- units: a program without G20/G21 gets a warning at its first move; --units
  in reads it in inches (same material removed as the mm program scaled),
  --units mm as mm, and neither warns; a program with G21 does not warn;
- bad offsets file: FILE:LINE error, exit 2, nothing written; bad options
  (--start, --g54, --units) name the flag, exit 2.
"""
import math
import os
import sys

import verifykit as vk

import pyopenvdb as vdb

swarf = sys.argv[1]
d = vk.workdir()


def run(program, args):
    """A run without a report: the material left, from the grid (pyopenvdb)."""
    r = vk.Run(swarf, program, args, d, report=False)
    r.left_mm3 = vk.grid_volume(r.out) if r.status == 0 else None  # mm^3 of material left
    return r



def material_at(path, p):
    g = vdb.read(path, "stock")
    vox = g.transform.voxelSize()[0]
    ijk = tuple(int(round(c / vox)) for c in p)
    return g.getConstAccessor().getValue(ijk) < 0


# ---- start position (CAMotics #454) ------------------------------------------
retract = "G21 G90\nT1 M6\nG0 Z50.000\nM2\n"
args = ["--stock", "box:-5,-5,0,125,65,6", "--tool", "T1=flat,D6,L20", "--voxel", "0.25"]
box454 = run("M2\n", args).left_mm3  # the untouched stock's grid volume
r = run(retract, args)
vk.check(r.status == 0, "retract-only: status %d %s" % (r.status, r.stderr))
vk.near(box454 - r.left_mm3, 0.0, 1e-3, "default start: the retract cuts nothing")
vk.check(material_at(r.out, (0, 0, 3)), "material still at the origin (pyopenvdb)")
vk.check(any(l.strip().startswith("start: tool tip at X0.000 Y0.000 Z16.000 (default")
             for l in r.stdout.splitlines()),
         "the summary says where the tool started (X0 Y0, 10 mm above the stock):\n" + r.stdout)
r = run(retract, args + ["--start", "0,0,0"])
# the hole's floor is the stock's bottom face at z = 0, a plane of voxel centres where the
# tip's face is too: the sheet of no thickness is cleared (stock.h, swarf_stock_clear_sheets),
# only the half voxels of the face outside the hole's rim stay: pi r^2 h within 0.5 %
phantom = math.pi * 9 * 6
vk.near(box454 - r.left_mm3, phantom, 0.005 * phantom, "--start 0,0,0: the phantom cut (pi r^2 h)")
vk.check(not material_at(r.out, (0, 0, 3)), "--start 0,0,0: a hole at the origin")
vk.check("start: tool tip at X0.000 Y0.000 Z0.000 (--start)" in r.stdout, "--start in the summary")
r = run("G21 G90\nG91 G0 X10\nG90 G0 Z50\nM2\n", args + ["--start", "20,30,10"])
vk.check(r.status == 0 and "path 50.0 mm" in r.stdout,
         "--start 20,30,10 then G91 X10 and Z50: a 50 mm path:\n" + r.stdout)

# ---- G53 and work offsets ------------------------------------------------------
stock = ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20", "--voxel", "0.25"]
prog = ("G21 G90 G54\n"
        "G53 G0 Z-3\n"        # machine Z-3: with G54 Z-50, 47 mm above the part
        "G0 X5 Y15\n"
        "G0 Z5\n"
        "G1 Z-2 F200\n"
        "G1 X35 F600\n"
        "G53 G0 Z-3\n"
        "M2\n")
BOX = run("M2\n", stock).left_mm3  # the untouched stock's grid volume
plain = run("G21 G90\nG0 Z5\nG0 X5 Y15\nG1 Z-2 F200\nG1 X35 F600\nG0 Z5\nM2\n", stock)
slot = BOX - plain.left_mm3
vk.check(plain.status == 0 and slot > 400, "the plain slot: %s mm^3" % slot)
g54 = run(prog, stock + ["--g54", "0,0,-50"])
vk.check(g54.status == 0, "--g54 0,0,-50: status %d %s" % (g54.status, g54.stderr))
vk.near(BOX - g54.left_mm3, slot, 1e-6 * slot, "--g54 0,0,-50: G53 Z-3 stays in the air, the slot as planned")
vk.check("rapid move" not in g54.stderr, "no rapid alarm: %s" % g54.stderr)
var = os.path.join(d, "machine.var")
with open(var, "w") as f:
    f.write("5220\t1.000000\n5221\t0.000000\n5222\t0.000000\n5223\t-50.000000\n")
off = run(prog, stock + ["--offsets", var])
vk.near(BOX - off.left_mm3, slot, 1e-6 * slot, "--offsets with 5223 -50: the same")
none = run(prog, stock)
vk.check(none.status == 0 and BOX - none.left_mm3 > slot + 20,
         "no offsets: G53 Z-3 plunges (%s mm^3)" % (BOX - none.left_mm3))
vk.check(":2:5: warning: rapid move (G0) cuts into the material" in none.stderr,
         "no offsets: rapid alarm at line 2 (G0 of G53 G0): %s" % none.stderr)
# G54 X10 moves the slot by 10 mm (the stock stays in the G54 frame)
shifted = run(prog, stock + ["--g54", "10,0,-50"])
vk.near(BOX - shifted.left_mm3, slot, 1e-6 * slot, "--g54 10,0,-50: the slot in the G54 frame, same volume")
# the work frame is G54: a program in G55 (from the file) lands 100 mm off the part
var55 = os.path.join(d, "g55.var")
with open(var55, "w") as f:
    f.write("5223 -50\n5241 100\n5243 -50\n")
g55 = run(prog.replace("G54", "G55"), stock + ["--offsets", var55])
vk.near(BOX - g55.left_mm3, 0.0, 1e-3, "G55 at X+100 from G54: the slot misses the part")

# ---- units -----------------------------------------------------------------------
inch_prog = "G0 Z0.2\nG0 X0.2 Y0.6\nG1 Z-0.08 F8\nG1 X1.4 F24\nG0 Z0.2\nM2\n"
mm_prog = "G21\n" + "".join(
    "%s\n" % " ".join(w[0] + ("%g" % (float(w[1:]) * 25.4) if w[0] in "XYZF" else w[1:])
                       for w in l.split()) for l in inch_prog.splitlines()[:-1]) + "M2\n"
ref = run(mm_prog, stock)
vk.check(ref.status == 0 and ref.warnings("G20") == [], "a program with G21 does not warn")
no_units = run(inch_prog, stock)
w = no_units.warnings("G20/G21")
vk.check(len(w) == 1 and ":1:1: warning:" in w[0], "no units word: one warning at 1:1: %s" % w)
inch = run(inch_prog, stock + ["--units", "in"])
vk.check(inch.status == 0 and inch.warnings("G20/G21") == [], "--units in: no warning")
vk.check(BOX - ref.left_mm3 > 100, "the mm program cuts (%g mm^3)" % (BOX - ref.left_mm3))
vk.near(inch.left_mm3, ref.left_mm3, 1e-6 * BOX, "--units in reads inches (= the mm program)")
mm = run(inch_prog, stock + ["--units", "mm"])
vk.check(mm.status == 0 and mm.warnings("G20/G21") == [], "--units mm: no warning")
vk.near(mm.left_mm3, no_units.left_mm3, 1e-9, "--units mm = the default")
vk.check(abs(mm.left_mm3 - ref.left_mm3) > 10, "mm and in differ")

# ---- bad input ---------------------------------------------------------------------
bad = os.path.join(d, "bad.var")
with open(bad, "w") as f:
    f.write("5221 10.0\n5222 ten\n")
r = vk.Run(swarf, prog, stock + ["--offsets", bad], d)
vk.check(r.status == 2, "bad offsets file: status %d" % r.status)
vk.check(r.stderr.startswith(bad + ":2:"), "error at FILE:LINE: %s" % r.stderr.strip())
vk.check(not os.path.exists(r.out) and not os.path.exists(r.json), "nothing written (grid, report)")
r = vk.Run(swarf, prog, stock + ["--offsets", os.path.join(d, "missing.var")], d, report=False)
vk.check(r.status == 2 and "missing.var" in r.stderr and not os.path.exists(r.out),
         "missing offsets file: %s" % r.stderr.strip())
for flag, val in (("--start", "1,2"), ("--start", "1,2,x"), ("--g54", "0,0"), ("--units", "cm")):
    r = vk.Run(swarf, prog, stock + [flag, val], d, report=False)
    vk.check(r.status == 2 and flag in r.stderr and not os.path.exists(r.out),
             "%s %s: status %d, %s" % (flag, val, r.status, r.stderr.strip()))
sys.exit(vk.done())
