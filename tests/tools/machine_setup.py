#!/usr/bin/python3
"""machine_setup.py SWARF -- the machine's setup in `swarf simulate`:

- start position: a program whose origin is inside the stock (CAMotics
  #454's reproduction: stock -5,-5,0..125,65,6, the only motion a retract)
  cuts nothing before its first move by default (the grid read with pyopenvdb
  still has material at the origin), and the summary says where it started;
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


def material_at(path, p):
    g = vdb.read(path, "stock")
    vox = g.transform.voxelSize()[0]
    ijk = tuple(int(round(c / vox)) for c in p)
    return g.getConstAccessor().getValue(ijk) < 0


# ---- start position (CAMotics #454) ------------------------------------------
retract = "G21 G90\nT1 M6\nG0 Z50.000\nM2\n"
args = ["--stock", "box:-5,-5,0,125,65,6", "--tool", "T1=flat,D6,L20", "--voxel", "0.25"]
r = vk.Run(swarf, retract, args, d)
vk.check(r.status == 0, "retract-only: status %d %s" % (r.status, r.stderr))
vk.near(r.removed(), 0.0, 1e-6, "default start: the retract cuts nothing")
vk.check(material_at(r.out, (0, 0, 3)), "material still at the origin (pyopenvdb)")
st = r.report["summary"]["start"]
vk.check(st["default"] and st["at"][0] == 0 and st["at"][1] == 0 and st["at"][2] > 6,
         "start X0 Y0 above the stock: %s" % st)
vk.check(any(l.strip().startswith("start") and "above the stock" in l for l in r.stdout.splitlines()),
         "the summary says where the tool started:\n" + r.stdout)
r = vk.Run(swarf, retract, args + ["--start", "0,0,0"], d)
vk.near(r.removed(), math.pi * 9 * 6, 0.01 * math.pi * 9 * 6, "--start 0,0,0: the phantom cut (pi r^2 h)")
vk.check(not material_at(r.out, (0, 0, 3)), "--start 0,0,0: a hole at the origin")
vk.check(r.report["summary"]["start"] == {"at": [0, 0, 0], "default": False}, "start in the report")
r = vk.Run(swarf, "G21 G90\nG91 G0 X10\nG90 G0 Z50\nM2\n", args + ["--start", "20,30,10"], d)
vk.check(r.status == 0 and r.report["summary"]["path_mm"] == 10 + 40,
         "--start 20,30,10 then G91 X10 and Z50: path %s" % (r.report and r.report["summary"]["path_mm"]))

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
plain = vk.Run(swarf, "G21 G90\nG0 Z5\nG0 X5 Y15\nG1 Z-2 F200\nG1 X35 F600\nG0 Z5\nM2\n", stock, d)
slot = plain.removed()
vk.check(plain.status == 0 and slot > 400, "the plain slot: %s mm^3" % slot)
g54 = vk.Run(swarf, prog, stock + ["--g54", "0,0,-50"], d)
vk.check(g54.status == 0, "--g54 0,0,-50: status %d %s" % (g54.status, g54.stderr))
vk.near(g54.removed(), slot, 1e-6 * slot, "--g54 0,0,-50: G53 Z-3 stays in the air, the slot as planned")
vk.check(g54.report["alarms"] == [], "no rapid alarm: %s" % g54.report["alarms"])
var = os.path.join(d, "machine.var")
with open(var, "w") as f:
    f.write("5220\t1.000000\n5221\t0.000000\n5222\t0.000000\n5223\t-50.000000\n")
off = vk.Run(swarf, prog, stock + ["--offsets", var], d)
vk.near(off.removed(), slot, 1e-6 * slot, "--offsets with 5223 -50: the same")
vk.check(off.report["inputs"]["offsets"] == var, "the offsets file in the report's inputs")
none = vk.Run(swarf, prog, stock, d)
vk.check(none.status == 0 and none.removed() > slot + 20, "no offsets: G53 Z-3 plunges (%s mm^3)" % none.removed())
vk.check(any(a["kind"] == "rapid" and a["line"] == 2 for a in none.report["alarms"]),
         "no offsets: rapid alarm at line 2")
# G54 X10 moves the slot by 10 mm (the stock stays in the G54 frame)
shifted = vk.Run(swarf, prog, stock + ["--g54", "10,0,-50"], d)
vk.near(shifted.removed(), slot, 1e-6 * slot, "--g54 10,0,-50: the slot in the G54 frame, same volume")
vk.check(shifted.report["summary"]["start"]["at"][0] == 0, "start X0 of the G54 frame")
# the work frame is G54: a program in G55 (from the file) lands 100 mm off the part
var55 = os.path.join(d, "g55.var")
with open(var55, "w") as f:
    f.write("5223 -50\n5241 100\n5243 -50\n")
g55 = vk.Run(swarf, prog.replace("G54", "G55"), stock + ["--offsets", var55], d)
vk.near(g55.removed(), 0.0, 1e-6, "G55 at X+100 from G54: the slot misses the part")

# ---- units -----------------------------------------------------------------------
inch_prog = "G0 Z0.2\nG0 X0.2 Y0.6\nG1 Z-0.08 F8\nG1 X1.4 F24\nG0 Z0.2\nM2\n"
mm_prog = "G21\n" + "".join(
    "%s\n" % " ".join(w[0] + ("%g" % (float(w[1:]) * 25.4) if w[0] in "XYZF" else w[1:])
                       for w in l.split()) for l in inch_prog.splitlines()[:-1]) + "M2\n"
ref = vk.Run(swarf, mm_prog, stock, d)
vk.check(ref.status == 0 and ref.warnings("G20") == [], "a program with G21 does not warn")
no_units = vk.Run(swarf, inch_prog, stock, d)
w = no_units.warnings("G20/G21")
vk.check(len(w) == 1 and ":1:1: warning:" in w[0], "no units word: one warning at 1:1: %s" % w)
vk.check(no_units.report["summary"]["units_warning_line"] == 1, "the warning in the report")
inch = vk.Run(swarf, inch_prog, stock + ["--units", "in"], d)
vk.check(inch.status == 0 and inch.warnings("G20/G21") == [], "--units in: no warning")
vk.near(inch.removed(), ref.removed(), 1e-6 * ref.removed(), "--units in reads inches (= the mm program)")
mm = vk.Run(swarf, inch_prog, stock + ["--units", "mm"], d)
vk.check(mm.status == 0 and mm.warnings("G20/G21") == [], "--units mm: no warning")
vk.near(mm.removed(), no_units.removed(), 1e-9, "--units mm = the default")
vk.check(inch.report["inputs"]["units"] == "in", "units in the report's inputs")

# ---- bad input ---------------------------------------------------------------------
bad = os.path.join(d, "bad.var")
with open(bad, "w") as f:
    f.write("5221 10.0\n5222 ten\n")
r = vk.Run(swarf, prog, stock + ["--offsets", bad], d)
vk.check(r.status == 2, "bad offsets file: status %d" % r.status)
vk.check(r.stderr.startswith(bad + ":2:"), "error at FILE:LINE: %s" % r.stderr.strip())
vk.check(not os.path.exists(r.out) and r.report is None, "nothing written")
r = vk.Run(swarf, prog, stock + ["--offsets", os.path.join(d, "missing.var")], d)
vk.check(r.status == 2 and "missing.var" in r.stderr and not os.path.exists(r.out),
         "missing offsets file: %s" % r.stderr.strip())
for flag, val in (("--start", "1,2"), ("--start", "1,2,x"), ("--g54", "0,0"), ("--units", "cm")):
    r = vk.Run(swarf, prog, stock + [flag, val], d)
    vk.check(r.status == 2 and flag in r.stderr and not os.path.exists(r.out),
             "%s %s: status %d, %s" % (flag, val, r.status, r.stderr.strip()))
sys.exit(vk.done())
