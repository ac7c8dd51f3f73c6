#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""report.py SWARF -- `swarf simulate --report FILE.json`, read back with
Python's json module (an independent reader):

- per-line removed volumes against analytic volumes: a flat cutter's plunge
  (a cylinder, pi r^2 d) and the slot that follows (the rectangle 30 x 2r x d:
  it adds a half disk at its end and takes the half of the plunge's disk that
  lies in the rectangle, already gone); the lines the tool moves through air
  remove 0;
- lines sum to the summary's removed volume, tools sum to the lines, the
  summary's removed volume matches the grid's (pyopenvdb, the inside-fraction
  estimate recomputed here); times and paths at programmed feeds;
- two tools: per tool totals; a line that runs many times (a loop) is one
  entry per tool;
- alarms: a rapid into material at a known line and column, with a depth
  and a place inside the cut; the peak removal-rate line in the summary;
- the inputs as given; a failed run writes no report.
"""
import math
import os
import sys

import verifykit as vk


swarf = sys.argv[1]
d = vk.workdir()
R, DEPTH = 3.0, 2.0
STOCK = "box:0,0,-10,40,30,0"
common = ["--stock", STOCK, "--tool", "T1=flat,D6,L20", "--voxel", "0.2", "--quiet"]

slot = ("G21 G90 G17\n"      # 1
        "G0 Z5\n"            # 2
        "G0 X5 Y15\n"        # 3
        "G1 Z-2 F200\n"      # 4  plunge: cylinder
        "G1 X35 F600\n"      # 5  slot: box + half disk
        "G0 Z5\n"            # 6
        "M30\n")
r = vk.Run(swarf, slot, common, d)
vk.check(r.status == 0 and r.report is not None, "slot run: status %d %s" % (r.status, r.stderr))
lines = r.lines()
plunge = math.pi * R * R * DEPTH
groove = 30 * 2 * R * DEPTH
# voxel estimate of curved walls: ~0.1 % of a cylinder's volume at 0.2 mm
vk.near(lines.get(4), plunge, 0.01 * plunge, "line 4 (plunge) removes pi r^2 d")
vk.near(lines.get(5), groove, 0.005 * groove, "line 5 (slot) removes the rectangle 30 x 2r x d")
for n in (2, 3, 6):
    vk.near(lines.get(n, 0.0), 0.0, 1e-9, "line %d moves in the air: removes nothing" % n)
total = r.removed()
vk.near(sum(lines.values()), total, 1e-6 * total, "lines sum to the summary's removed volume")
vk.near(total, plunge + groove, 0.005 * (plunge + groove), "removed volume, analytic")

# the grid itself, read with pyopenvdb: volume = voxel^3 sum clamp(1/2 - v / voxel, 0, 1)
left = vk.grid_volume(r.out)
vk.near(left, r.report["summary"]["volume_after_mm3"], 1e-6 * left,
        "the summary's volume after = the grid's (pyopenvdb)")

by_line = {e["line"]: e for e in r.report["lines"]}
vk.near(by_line[4]["time_s"], 7 / 200 * 60, 1e-9, "line 4 time: 7 mm at F200")
vk.near(by_line[5]["time_s"], 30 / 600 * 60, 1e-9, "line 5 time: 30 mm at F600")
vk.near(by_line[5]["path_mm"], 30, 1e-9, "line 5 path")
vk.check(all(e["tool"] == 1 for e in r.report["lines"]), "every line with T1")
tools = r.report["tools"]
vk.check(len(tools) == 1 and tools[0]["tool"] == 1, "one tool: %s" % tools)
vk.near(tools[0]["removed_mm3"], total, 1e-6 * total, "T1 removed everything")
vk.near(tools[0]["time_s"], r.report["summary"]["machining_s"], 1e-9, "T1 time = machining time")
s = r.report["summary"]
vk.check(s["moves"] == 5 and s["rapids"] == 3, "moves %s, rapids %s" % (s["moves"], s["rapids"]))
vk.check(s["peak_mrr"]["line"] == 5, "peak removal rate on line 5: %s" % s["peak_mrr"])
vk.near(s["peak_mrr"]["mm3_per_min"], lines[5] / 3.0 * 60, 1e-6 * lines[5], "peak rate value")
vk.check("peak removal rate" not in r.stdout, "--quiet prints no summary")
vk.check(s["start"]["default"] is True and s["start"]["at"][2] > 0, "default start: %s" % s["start"])
inp = r.report["inputs"]
vk.check(inp["stock"] == STOCK and inp["tools"] == ["T1=flat,D6,L20"] and inp["voxel"] == 0.2
         and inp["machine"] == "xyz" and inp["program"] == r.program and inp["version"],
         "inputs: %s" % inp)
vk.check(r.report["alarms"] == [], "no alarm")

# the summary printed: the peak rate line
r2 = vk.Run(swarf, slot, common[:-1], d)
vk.check(any("peak removal rate" in l and "line 5" in l for l in r2.stdout.splitlines()),
         "summary names the peak removal rate line:\n" + r2.stdout)

# two tools, a loop, a rapid into material
prog = ("G21 G90\n"                           # 1
        "T1 M6\n"                             # 2
        "G0 Z5\n"                             # 3
        "G0 X10 Y10\n"                        # 4
        "G0 Z-1\n"                            # 5  rapid plunge: alarm, cylinder r 3 depth 1
        "G0 Z5\n"                             # 6
        "T2 M6\n"                             # 7
        "#1 = 0\n"                            # 8
        "o100 while [#1 LT 3]\n"              # 9
        "G0 X[20 + #1 * 8] Y20\n"             # 10
        "G1 Z-1 F100\n"                       # 11 three plunges, cylinders r 1 depth 1
        "G0 Z5\n"                             # 12
        "#1 = [#1 + 1]\n"                     # 13
        "o100 endwhile\n"                     # 14
        "M30\n")
r = vk.Run(swarf, prog, ["--stock", STOCK, "--tool", "T1=flat,D6,L20", "--tool", "T2=flat,D2,L10",
                         "--voxel", "0.2", "--quiet"], d)
vk.check(r.status == 0 and r.report is not None, "two tools: status %d %s" % (r.status, r.stderr))
ents = [e for e in r.report["lines"] if e["line"] == 11]
vk.check(len(ents) == 1 and ents[0]["tool"] == 2 and ents[0]["moves"] == 3,
         "line 11 in a loop: one entry, 3 moves, T2: %s" % ents)
vk.near(ents[0]["removed_mm3"], 3 * math.pi * 1 * 1, 0.03 * 3 * math.pi, "line 11: three r1 d1 plunges")
l5 = r.lines().get(5)
vk.near(l5, math.pi * 9 * 1, 0.01 * math.pi * 9, "line 5: the rapid's r3 d1 plunge")
tools = {t["tool"]: t for t in r.report["tools"]}
vk.check(set(tools) == {1, 2}, "tools 1 and 2: %s" % list(tools))
vk.near(tools[1]["removed_mm3"], l5, 1e-9, "T1's volume is line 5's")
vk.near(tools[1]["removed_mm3"] + tools[2]["removed_mm3"], r.removed(), 1e-6 * r.removed(),
        "tools sum to the total")
vk.near(sum(t["path_mm"] for t in tools.values()), r.report["summary"]["path_mm"], 1e-9,
        "tool paths sum to the path")
al = r.report["alarms"]
vk.check(len(al) == 1 and al[0]["kind"] == "rapid" and al[0]["line"] == 5 and al[0]["column"] == 1,
         "one rapid alarm at 5:1: %s" % al)
if al:
    a = al[0]
    vk.check(a["depth_mm"] is None or 0 < a["depth_mm"] <= 1.0 + 0.2, "alarm depth %s" % a["depth_mm"])
    vk.check(a["at"] is None or (math.hypot(a["at"][0] - 10, a["at"][1] - 10) <= 3.2 and
                                 -1.2 <= a["at"][2] <= 0.2), "alarm place %s" % a["at"])
vk.check(r.report["summary"]["alarm_counts"]["rapid"] == 1, "alarm counts")

# a failed run (bad G-code at line 3) writes no report
r = vk.Run(swarf, "G0 Z5\nG1 X1 F100\nG1 Q\n", common, d)
vk.check(r.status == 2 and not os.path.exists(r.json) and not os.path.exists(r.out),
         "bad program: status %d, no report, no grid" % r.status)
# an unwritable report folder is refused before the run
r = vk.Run(swarf, slot, common + ["--report", "/nonexistent/r.json"], d, report=False)
vk.check(r.status == 2 and "--report" in r.stderr and not os.path.exists(r.out),
         "unwritable --report: status %d, %s" % (r.status, r.stderr.strip()))
# Rotary moves' times follow LinuxCNC's feed rule (LinuxCNC's
# G-code manual, "Feed Rate"): under G94, when any of X Y Z moves F is in mm/min
# along the X Y Z path and the rotary axes keep step; when only rotary axes
# move, F is in degrees/min along them; under G93 a move takes 1/F minutes.
# The worked cases: X10 with A90 at F100 takes 10/100 min = 6 s (not 90.6/100);
# A90 alone at F100 takes 90/100 min = 54 s; G93 F2 takes 0.5 min = 30 s.
rot = ("G21 G90 G94\nG0 X0 Y0 Z20 A0\nG1 X10 A90 F100\nG1 A180 F100\n"
       "G93 G1 X20 A360 F2\nG94 G1 X30 F600\nM2\n")
for machine, stock in (("xyza", "cylinder:x,10,0,40"), ("xyzac-trt", "cylinder:z,42,0,30")):
    prog = rot.replace(" A", " C") if machine == "xyzac-trt" else rot
    r = vk.Run(swarf, prog, ["--machine", machine, "--stock", stock, "--tool", "T1=ball,D4,L30",
                             "--voxel", "0.5"], d)
    if vk.check(r.status == 0 and r.report, "%s rotary program: %s" % (machine, r.stderr[-200:])):
        t = {e["line"]: e["time_s"] for e in r.report["lines"]}
        for line, want, what in ((3, 6.0, "X10 with a rotary move at F100: X's 10 mm"),
                                 (4, 54.0, "a rotary move alone at F100: 90 degrees"),
                                 (5, 30.0, "G93 F2: half a minute"), (6, 1.0, "G94 X10 at F600")):
            vk.near(t.get(line, -1), want, 1e-9, "%s line %d: %s (s)" % (machine, line, what))
leftovers = [f for f in os.listdir(d) if ".tmp" in f]
vk.check(leftovers == [], "no temporary files left: %s" % leftovers)
sys.exit(vk.done())
