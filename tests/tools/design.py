#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""design.py SWARF -- `swarf simulate --design FILE.stl`: gouges at known
lines with known depths, none on a program that stays on the design, and the
summary's gouge and excess against analytic values. Designs are STL meshes
written here (a faced box; a box with a pocket).

- faced box: the part is the stock less its top 1 mm. Facing at Z-1 gouges
  nothing; a pass at Z-1.3 on a known line gouges 0.3 mm there (flat floor:
  exact), its volume is the pass's footprint times 0.3; leaving half the
  top unfaced leaves an excess of 1 mm over a known area.
- pocket: milling the pocket to its floor and walls gouges nothing; a plunge
  0.5 mm below the floor and a pass 0.4 mm into a wall gouge 0.5 and 0.4 mm
  at their lines; each gouge is told once per program line, by the move that
  first cut into the design (a later move through the same place is not).
- without --report (only the gouges measured): the same warnings and summary.
- a retract from a pose whose tool surface passes through voxel centres
  inside the design (a tie: the cut's sdf is 0 there, its sign rounding's)
  gouges nothing and removes nothing: the gouges stay with the moves that
  cut, with and without --report.
- --fail-on gouge: exit status 4, outputs still written; --tolerance;
  the report's gouge alarms; a design that misses the stock is an error
  (exit 2, nothing written).
"""
import os
import re
import sys

import verifykit as vk

swarf = sys.argv[1]
d = vk.workdir()
VOX = 0.2
stock = "box:0,0,-10,40,30,0"
tool = "T1=flat,D6,L20"


def run(program, design, extra=(), report=True):
    return vk.Run(swarf, program, ["--stock", stock, "--tool", tool, "--voxel", str(VOX),
                                   "--design", design] + list(extra), d, report=report)


def same_without_report(r, program, design, what, extra=()):
    """Without --report only the gouges are measured (swarf_stock_remove_batch_gouges_support):
    the same warnings, line for line, depth for depth, and the same summary's design lines."""
    q = run(program, design, extra, report=False)
    design_lines = lambda t: [l for l in t.splitlines() if "design" in l and "CPU" not in l]
    vk.check(q.status == r.status and q.stderr == r.stderr and gouges(q) == gouges(r),
             "%s without --report: the same warnings\n%s\n---\n%s" % (what, q.stderr, r.stderr))
    vk.check(design_lines(q.stdout) == design_lines(r.stdout) and design_lines(q.stdout),
             "%s without --report: the same summary of the design\n%s\n---\n%s" %
             (what, q.stdout, r.stdout))


def gouges(r):
    """(line, column, depth) of each gouge warning, in order."""
    out = []
    for l in r.stderr.splitlines():
        m = re.match(r".*:(\d+):(\d+): warning: gouge (\d+\.\d{3}) mm into the design$", l)
        if m:
            out.append((int(m.group(1)), int(m.group(2)), float(m.group(3))))
    return out


# ---- faced box -------------------------------------------------------------
faced = os.path.join(d, "faced.stl")
vk.write_stl(faced, vk.box_triangles((0, 0, -10), (40, 30, -1)))


def facing(z, ys):
    """Zig-zag passes along X at Z=z, at each Y of ys, from outside the stock."""
    p = ["G21 G90", "G0 Z5", "G0 X-5 Y%g" % ys[0], "G1 Z%g F300" % z]
    for i, y in enumerate(ys):
        p.append("G1 Y%g" % y)
        p.append("G1 X%g" % (45 if i % 2 == 0 else -5))
    p += ["G0 Z5", "M30"]
    return "\n".join(p) + "\n", p


ys = [y * 0.5 for y in range(-4, 65, 8)]  # every 4 mm with a D6: full cover of 0..30
text, p = facing(-1, ys)
r = run(text, faced)
vk.check(r.status == 0, "facing at Z-1: status %d %s" % (r.status, r.stderr))
vk.check(gouges(r) == [], "facing on the design: no gouge: %s" % gouges(r))
des = r.report["summary"]["design"]
vk.near(des["gouge_mm3"], 0, 0.05, "no gouge volume")
vk.near(des["excess_mm3"], 0, 0.5, "no excess (the top is faced off)")
vk.check(r.report["summary"]["alarm_counts"]["gouge"] == 0, "no gouge alarm")

# a second program: faced at Z-1, then one pass at Z-1.3 along Y=15
lines = p[:-2] + ["G0 Z5", "G0 X-5 Y15", "G1 Z-1.3 F300", "G1 X45", "G0 Z5", "M30"]
prog = "\n".join(lines) + "\n"
deep_line = len(lines) - 2  # "G1 X45", 1-based
r = run(prog, faced)
g = gouges(r)
vk.check(r.status == 0, "pass at Z-1.3: status %d %s" % (r.status, r.stderr))
# the plunge at X-5 (outside the part: x < 0 is beyond the design) does not gouge;
# the pass does: 0.3 mm deep
vk.check(len(g) == 1 and g[0][0] == deep_line and g[0][1] == 1, "one gouge at line %d: %s" % (deep_line, g))
if g:
    vk.near(g[0][2], 0.3, 0.0015, "its depth (3 decimals)")
des = r.report["summary"]["design"]
# the pass's footprint over the part (40 mm long, 6 wide) times the depth beyond
# the tolerance (half a voxel): what lies deeper than the tolerance
vol = (0.3 - VOX / 2) * (40 * 6)
vk.near(des["gouge_mm3"], vol, 0.03 * vol, "gouge volume = footprint x 0.3")
vk.near(des["gouge_depth_mm"], 0.3, 0.0015, "deepest gouge")
# where: a voxel centre of the gouge (its depth adds the radius known to be clear)
vk.check(des["gouge_at"] is not None and 0 <= des["gouge_at"][0] <= 40 and
         abs(des["gouge_at"][1] - 15) <= 3 and -1.3 - 1e-9 <= des["gouge_at"][2] <= -1.0,
         "where: in the pass's footprint, between Z-1.3 and the design's face: %s" % des["gouge_at"])
al = [a for a in r.report["alarms"] if a["kind"] == "gouge"]
vk.check(len(al) == 1 and al[0]["line"] == deep_line, "one gouge alarm in the report: %s" % al)
vk.check(re.search(r"gouge .* deepest 0\.30\d mm", r.stdout) is not None,
         "summary gives the deepest gouge:\n" + r.stdout)
same_without_report(r, prog, faced, "pass at Z-1.3")

# excess: face only y >= 15 (passes at 18..33 cover y 15..36); the rest (y 0..15) keeps 1 mm
text, _ = facing(-1, [18, 22, 26, 30, 33])
r = run(text, faced)
des = r.report["summary"]["design"]
exc = 40 * 15 * 1.0  # minus the tolerance band (half a voxel) over the same area
vk.near(des["excess_mm3"], exc - 40 * 15 * VOX / 2, 0.01 * exc, "excess volume 40 x 15 x (1 - tol)")
vk.near(des["excess_mm"], 1.0, 0.01, "largest excess 1 mm")
vk.check(gouges(r) == [], "no gouge when leaving material")

# --tolerance: a 0.3 mm gouge within 0.35 is none
r = run(prog, faced, ["--tolerance", "0.35"])
vk.check(gouges(r) == [] and r.report["summary"]["design"]["gouge_mm3"] < 0.05,
         "--tolerance 0.35 hides the 0.3 mm gouge: %s, %s mm^3" %
         (gouges(r), r.report["summary"]["design"]["gouge_mm3"]))

# tolerances beyond half a voxel: the design's band grows with the tolerance
# (swarf_stock_design_band: 2 voxels at 0.15 to 0.3, 3 at 0.35), so that every
# voxel the volumes weigh (within the tolerance and half a voxel of the
# design's surface) is exact: gouge (0.3 - t) x the pass's footprint, excess
# (1 - t) x the unfaced area; a band too narrow for t reads deeper voxels as
# its edge and loses part of both
for t in (0.15, 0.25, 0.3, 0.35):
    r = run(prog, faced, ["--tolerance", str(t)])
    des = r.report["summary"]["design"]
    vol = max(0.0, 0.3 - t) * (40 * 6)
    vk.near(des["gouge_mm3"], vol, 0.03 * (0.3 - VOX / 2) * (40 * 6),
            "--tolerance %g: gouge volume = footprint x (0.3 - t)" % t)
    r = run(text, faced, ["--tolerance", str(t)])
    des = r.report["summary"]["design"]
    vk.near(des["excess_mm3"], 40 * 15 * (1.0 - t), 0.01 * exc,
            "--tolerance %g: excess volume 40 x 15 x (1 - t)" % t)
    vk.near(des["excess_mm"], 1.0, 0.01, "--tolerance %g: largest excess 1 mm" % t)

# --fail-on gouge: status 4, outputs written
r = run(prog, faced, ["--fail-on", "gouge"])
vk.check(r.status == 4 and os.path.exists(r.out) and r.report is not None,
         "--fail-on gouge: status %d, outputs written" % r.status)
r = run(text, faced, ["--fail-on", "gouge"])
vk.check(r.status == 0, "--fail-on gouge without a gouge: status %d" % r.status)

# ---- pocket ------------------------------------------------------------------
pocket = os.path.join(d, "pocket.stl")
tris = vk.pocket_box_triangles((0, 0, -10), (40, 30, 0), (10, 8), (30, 22), -5)
vk.write_stl(pocket, tris)
vk.near(vk.mesh_volume(tris), 40 * 30 * 10 - 20 * 14 * 5, 1e-6, "the pocket mesh is closed and oriented")


def pocket_program(extra):
    """Clear the pocket 10..30 x 8..22 to Z-5 with a D6: tool centres 3 mm inside."""
    p = ["G21 G90", "G0 Z5", "G0 X13 Y11", "G1 Z-5 F200"]
    for y in (11, 15, 19):
        p += ["G1 Y%g" % y, "G1 X27", "G1 X13"]
    p += ["G1 X13 Y11", "G1 X27", "G1 Y19", "G1 X13", "G1 Y11", "G0 Z5"]
    p += extra + ["M30"]
    return "\n".join(p) + "\n"


r = run(pocket_program([]), pocket)
vk.check(r.status == 0, "pocket: status %d %s" % (r.status, r.stderr))
vk.check(gouges(r) == [], "a pocket to its floor and walls gouges nothing: %s" % gouges(r))
base = len(pocket_program([]).splitlines()) - 1  # lines before the extra ones
extra = ["G0 X20 Y15", "G1 Z-5.5 F100",  # plunge 0.5 below the floor
         "G0 Z-4", "G1 X27.4",           # into the wall x = 30 by 0.4
         "G1 X20", "G1 X27.4",           # the same place again: no new gouge
         "G0 Z5"]
r = run(pocket_program(extra), pocket)
g = gouges(r)
want = [(base + 2, 0.5), (base + 4, 0.4)]
vk.check([x[0] for x in g] == [w[0] for w in want], "gouges at lines %s: %s" % ([w[0] for w in want], g))
for got, (line, depth) in zip(g, want):
    vk.near(got[2], depth, 0.002, "line %d: gouge depth (flat floor, flat wall: exact)" % line)
vk.check(r.report["summary"]["alarm_counts"]["gouge"] >= 2, "gouge alarms counted")
same_without_report(r, pocket_program(extra), pocket, "pocket plunge and wall")

# a design that misses the stock: exit 2, nothing written
far = os.path.join(d, "far.stl")
# A retract straight up from the end of a pass whose ball surface passes
# through voxel centres 1.4 mm inside the design (found by a random search:
# the retract was warned "gouge 1.400 mm" with nothing removed).
tie_design = os.path.join(d, "tie.stl")
vk.write_stl(tie_design, vk.box_triangles((0, 0, -10), (40, 40, -1)))
tie = "G21 G90\nG0 Z5\nG0 X20.0 Y26.0\nG1 Z-2.8 F100\nG1 X26.0 Y26.0 Z-2.8 F300\nG0 Z6\nM2\n"
for report in (True, False):
    r = vk.Run(swarf, tie, ["--stock", "box:0,0,-10,40,40,0", "--tool", "T1=ball,D3", "--voxel", "0.2",
                            "--design", tie_design], d, report=report)
    g = [line for line, _, _ in gouges(r)]
    what = "retract after a tie (%s --report)" % ("with" if report else "without")
    vk.check(r.status == 0 and 6 not in g, "%s: no gouge on the retract's line 6: %s" % (what, g))
    vk.check(4 in g and 5 in g, "%s: the plunge and the pass gouge (lines 4, 5): %s" % (what, g))
    if report:
        vk.check(r.lines().get(6, 0.0) == 0.0, "%s: line 6 removes nothing" % what)

vk.write_stl(far, vk.box_triangles((100, 100, -10), (140, 130, -1)))
r = run(text, far)
vk.check(r.status == 2 and not os.path.exists(r.out) and r.report is None,
         "design off the stock: status %d, nothing written: %s" % (r.status, r.stderr.strip()))
sys.exit(vk.done())
