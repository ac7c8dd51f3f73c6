#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""design_cache.py SWARF -- an STL design's band kept between runs
(--design-cache, swarf_sim_read_design_cached):

- the first run builds the band and keeps it in the cache folder (one
  KEY.band, swarf's own band file, read back in-process);
  the second finds it (the summary says so) and gives the same warnings,
  deviation, report and grid, byte for byte after the .vdb's UUID;
- the key is the design's bytes: a changed design is built anew, as is the
  same design at another voxel; --design-cache off neither reads nor writes;
- a damaged cache entry is rebuilt, never trusted (the run's results stay
  the cold run's); the design's triangles are kept beside the band in
  search order (KEY.tri) and read back; a damaged .tri is replaced by the
  STL's reading (same results), then written anew; --design-cache-max bounds the folder, oldest out first;
- the default folder is $XDG_CACHE_HOME/swarf/designs.
"""
import glob
import json
import os
import shutil
import sys

import verifykit as vk

swarf = sys.argv[1]
d = vk.workdir()
cache = os.path.join(d, "cache")
# a faced box (the stock less its top 1 mm) and two passes 0.3 mm below it (lines 5, 6)
PROGRAM = ("G21 G90\nG0 X0 Y15 Z5\nG1 Z-1 F300\nG1 X40\nG1 Y10 Z-1.3\nG1 X0\nG0 Z5\nM2\n")
design = os.path.join(d, "part.stl")
vk.write_stl(design, vk.box_triangles((0, 0, -10), (40, 30, -1)))


def run(tag, *extra, voxel="0.2"):
    r = vk.Run(swarf, PROGRAM, ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20",
                                "--voxel", voxel, "--design", design] + list(extra), d)
    vk.check(r.status == 0, "%s: exit 0 (%s)" % (tag, r.stderr.strip()[-200:]))
    with open(r.out, "rb") as f:
        grid = f.read()[57:]
    return r, grid


def entries(folder=cache):
    return sorted(glob.glob(os.path.join(folder, "*.band")))


def same(a, b, what):
    ra, ga = a
    rb, gb = b
    vk.check(ra.warnings("gouge") == rb.warnings("gouge") and len(ra.warnings("gouge")) == 2,
             "%s: the same gouge warning: %s" % (what, rb.warnings("gouge")))
    for k in ("summary", "alarms", "lines"):
        vk.check(ra.report[k] == rb.report[k] or k == "summary" and
                 {x: v for x, v in ra.report[k].items() if not x.endswith("_s")} ==
                 {x: v for x, v in rb.report[k].items() if not x.endswith("_s")},
                 "%s: the same report %s" % (what, k))
    vk.check(ga == gb, "%s: the same grid, byte for byte" % what)


cold = run("cold", "--design-cache", cache)
vk.check("from the design cache" not in cold[0].stdout and len(entries()) == 1,
         "cold: built, one entry kept: %s" % entries())
warm = run("warm", "--design-cache", cache)
vk.check("its band from the design cache" in warm[0].stdout, "warm: the summary says so")
same(cold, warm, "warm against cold")

# the triangles beside the band (KEY.tri, 12 of them, in search order): a warm
# run reads them back; a damaged file costs a reading of the STL (the same
# results) and goes, and the next run writes it anew
tri = entries()[0][:-5] + ".tri"
vk.check(os.path.isfile(tri) and os.path.getsize(tri) == 40 + 36 * 12,
         "cold: the triangles kept beside the band (%s)" % os.listdir(cache))
with open(tri, "r+b") as f:
    f.seek(50)
    f.write(b"\xff" * 8)
hurt = run("damaged triangles", "--design-cache", cache)
same(cold, hurt, "damaged triangles against cold")
vk.check(not os.path.exists(tri), "the damaged triangles are removed")
run("after the damaged triangles", "--design-cache", cache)
vk.check(os.path.isfile(tri) and os.path.getsize(tri) == 40 + 36 * 12,
         "the triangles are written anew by the next run")
off = run("off", "--design-cache", "off")
vk.check("from the design cache" not in off[0].stdout, "off: not read from the cache")
same(cold, off, "off against cold")

# another voxel, then a changed design: new entries, never the old band
run("0.25 mm", "--design-cache", cache, voxel="0.25")
vk.check(len(entries()) == 2, "another voxel: a second entry (%d)" % len(entries()))
vk.write_stl(design, vk.box_triangles((0, 0, -10), (40, 30, -1.5)))
changed = run("changed design", "--design-cache", cache)
vk.check("from the design cache" not in changed[0].stdout and len(entries()) == 3,
         "a changed design is built anew (%d entries)" % len(entries()))
vk.check(changed[0].warnings("gouge") == [], "the changed design (top at -1.5) is not gouged")
vk.write_stl(design, vk.box_triangles((0, 0, -10), (40, 30, -1)))

# a damaged entry: rebuilt, and the run is the cold run
for e in entries():
    with open(e, "r+b") as f:
        f.seek(200)
        f.write(b"\xff" * 64)
damaged = run("damaged entry", "--design-cache", cache)
vk.check("from the design cache" not in damaged[0].stdout, "a damaged entry is not used")
same(cold, damaged, "damaged entry against cold")
again = run("after the damage", "--design-cache", cache)
vk.check("its band from the design cache" in again[0].stdout, "the rebuilt entry is used next")

# the bound: 1 MB holds one entry of these (each ~0.4 MB at 0.2 mm, more at 0.1)
sizes = [os.path.getsize(e) for e in entries()]
run("bounded", "--design-cache", cache, "--design-cache-max", "1", voxel="0.1")
kept = entries()
vk.check(sum(os.path.getsize(e) for e in kept) <= 1024 * 1024 or len(kept) == 1,
         "--design-cache-max 1: the folder within 1 MB or its newest entry only (%d entries, "
         "sizes before %s)" % (len(kept), sizes))

# the default folder
xdg = os.path.join(d, "xdg")
os.environ["XDG_CACHE_HOME"] = xdg
run("default folder")
vk.check(len(entries(os.path.join(xdg, "swarf", "designs"))) == 1,
         "the default folder is $XDG_CACHE_HOME/swarf/designs")
shutil.rmtree(d, ignore_errors=True)
vk.done()
