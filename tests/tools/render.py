#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""render.py SWARF -- `swarf render --view NAME` and `--design`: the pictures
read back with a PNG decoder written here (Python's zlib; no imaging library)
and checked against the part's known geometry.

- A box 40 x 30 x 10 mm with a pocket cut at X6..18 Y6..14 (bottom left seen
  from above), 3 mm deep. Views: the box's silhouette has the aspect of the
  face each view looks at (top 40:30, front 40:10, left 30:10); in the top
  view the pocket's pixels (those differing from the uncut box's picture)
  lie where the pocket is, X to the right, Y up; iso differs from top.
- Deviation colours: the same grid against two designs written as STL, a
  pocket floor 1 mm higher than cut (a 1 mm gouge) and 1 mm lower (1 mm of
  excess). The floor is blue (gouge) or red (excess), the untouched top
  green; the legend's bar is red at its top, blue at its bottom, so the
  floor's colour matches the legend's half of its sign.
- Meshes by extension (--mesh .stl, .obj, .ply), read back here: each
  encloses the box less the pocket (analytic, the tool's rounded corners
  included); with a design the PLY's floor vertices carry -1 mm and blue.
- swarf compare against a .vdb design (the uncut box): the pocket is a
  gouge of its area x (depth - tolerance), "or more" deep (beyond the
  design's band), the same volume as --design; each line's warning says
  "or more" too.
- Bad view names: exit 2, no picture.
"""
import math
import os
import subprocess
import sys

import stock_check
import verifykit as vk

swarf = sys.argv[1]
d = vk.workdir()
W, H = 400, 300


def render(grid, name, extra=()):
    out = os.path.join(d, name + ".png")
    if os.path.exists(out):
        os.unlink(out)
    p = subprocess.run([swarf, "render", grid, "--image", out, "--size", "%dx%d" % (W, H)] + list(extra),
                       capture_output=True, text=True, timeout=300)
    vk.check(p.returncode == 0 and os.path.exists(out), "render %s: exit %d %s" % (name, p.returncode, p.stderr.strip()))
    return vk.read_png(out) if os.path.exists(out) else (0, 0, [])


def silhouette(img):
    """Bounding box (x0, y0, x1, y1, pixels) of what is not background: the
    background is a vertical gradient, so a row's background is its first
    pixel's colour."""
    w, h, rows = img
    xs, ys = [], []
    for y, row in enumerate(rows):
        bg = row[0]
        for x, c in enumerate(row):
            if max(abs(c[k] - bg[k]) for k in range(3)) > 3:
                xs.append(x), ys.append(y)
    return (min(xs), min(ys), max(xs), max(ys)) if xs else None


def enclosed(pts, tris):
    """Volume enclosed by oriented triangles (divergence theorem)."""
    v = 0.0
    for t in tris:
        a, b, c = (pts[i] for i in t)
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0]))
    return v / 6.0


def simulate(program, out):
    r = vk.Run(swarf, program, ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20",
                                "--voxel", "0.2"], d, report=False)
    vk.check(r.status == 0, "simulate: exit %d %s" % (r.status, r.stderr.strip()[-300:]))
    path = os.path.join(d, out)
    os.rename(r.out, path)
    return path


# The pocket: a D6 tool's centre over X9..15 Y9..11 at Z-3 clears X6..18 Y6..14.
program_pocket = "G21 G90\nG0 Z5\nG0 X9 Y9\nG1 Z-3 F300\nG1 X15\nG1 Y11\nG1 X9\nG1 Y9\nG0 Z5\nM30\n"
pocket = simulate(program_pocket, "pocket.vdb")
plain = simulate("G21 G90\nG0 Z5\nG0 X50 Y50\nM30\n", "b.vdb")  # cuts nothing

# ---- views: silhouettes with each face's aspect -----------------------------
for view, (a, b) in {"top": (40, 30), "bottom": (40, 30), "front": (40, 10), "back": (40, 10),
                     "left": (30, 10), "right": (30, 10)}.items():
    box = silhouette(render(plain, "plain_" + view, ["--view", view]))
    if not vk.check(box is not None, "%s view shows the box" % view):
        continue
    bw, bh = box[2] - box[0] + 1, box[3] - box[1] + 1
    vk.near(bw / bh, a / b, 0.03 * a / b, "%s view: silhouette %dx%d px, aspect of the %gx%g mm face" % (view, bw, bh, a, b))

top_plain = render(plain, "plain_top", ["--view", "top"])
top = render(pocket, "pocket_top", ["--view", "top"])
box = silhouette(top_plain)
px = (box[2] - box[0] + 1) / 40.0  # pixels a mm
changed = [(x, y) for y in range(H) for x in range(W) if top[2][y][x] != top_plain[2][y][x]]
vk.check(len(changed) > 0, "top view: the pocket changes %d pixels" % len(changed))
if changed:
    x0 = box[0] + 6 * px
    x1 = box[0] + 18 * px
    y0 = box[3] - 14 * px  # Y up: image rows grow downward
    y1 = box[3] - 6 * px
    cx = [x for x, _ in changed]
    cy = [y for _, y in changed]
    for got, want, what in ((min(cx), x0, "left edge X6"), (max(cx), x1, "right edge X18"),
                            (min(cy), y0, "far edge Y14"), (max(cy), y1, "near edge Y6")):
        vk.near(got, want, 2.5, "top view: changed pixels' %s (px)" % what)
iso = render(pocket, "pocket_iso", ["--view", "iso"])
vk.check(iso[2] != top[2] and silhouette(iso) is not None, "iso view: a picture of its own")


# ---- deviation colours ------------------------------------------------------
def hue(c):
    r, g, b = c
    if b > r + 40 and b > g + 10:
        return "blue"
    if r > b + 40 and r > g + 30:
        return "red"
    if g > r + 20 and g > b + 20:
        return "green"
    return "other"


def pixel(img, x_mm, y_mm):
    return img[2][int(round(box[3] - y_mm * px))][int(round(box[0] + x_mm * px))]


def legend_bar(img):
    """The legend's colour bar: a column in the right quarter holding both
    red and blue pixels; the rows of its red and of its blue pixels."""
    w, h, rows = img
    for x in range(3 * w // 4, w):
        red = [y for y in range(h) if hue(rows[y][x]) == "red"]
        blue = [y for y in range(h) if hue(rows[y][x]) == "blue"]
        if red and blue:
            return red, blue
    return None, None


for floor, sign in ((-2, "blue"), (-4, "red")):
    design = os.path.join(d, "design%d.stl" % -floor)
    vk.write_stl(design, vk.pocket_box_triangles((0, 0, -10), (40, 30, 0), (6, 6), (18, 14), floor))
    img = render(pocket, "design%d" % -floor, ["--view", "top", "--design", design])
    what = "gouge" if sign == "blue" else "excess"
    floor_c = pixel(img, 12, 10)
    vk.check(hue(floor_c) == sign, "design floor at Z%d (1 mm %s): the pocket floor is %s: %s" %
             (floor, what, sign, floor_c))
    top_c = pixel(img, 30, 22)
    vk.check(hue(top_c) == "green", "the untouched top (on the design) is green: %s" % (top_c,))
    red, blue = legend_bar(img)
    vk.check(red is not None and max(red) < min(blue),
             "the legend's bar: red (excess) above blue (gouge): red rows %s, blue rows %s" %
             (red and (min(red), max(red)), blue and (min(blue), max(blue))))

# ---- meshes by extension, and swarf compare -------------------------------
# The pocket's volume: 12 x 8 mm less the D6 tool's rounded corners, 3 deep.
POCKET_AREA = 12 * 8 - (4 - math.pi) * 9
box_less_pocket = 40 * 30 * 10 - 3 * POCKET_AREA
meshes = {}
for ext in ("stl", "obj", "ply"):
    path = os.path.join(d, "pocket." + ext)
    r = vk.Run(swarf, program_pocket, ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20",
                                       "--voxel", "0.2", "--mesh", path], d, report=False)
    if vk.check(r.status == 0 and os.path.exists(path), "--mesh pocket.%s written" % ext):
        pts, tris, verts = stock_check.read_ply(path) if ext == "ply" else \
            stock_check.read_obj(path) if ext == "obj" else stock_check.read_stl(path)
        meshes[ext] = (len(tris), enclosed(pts, tris))
for ext, (n, vol) in meshes.items():
    vk.near(vol, box_less_pocket, 0.002 * box_less_pocket,
            "%s: %d triangles enclose the box less the pocket (mm^3)" % (ext, n))
vk.check(len(set(n for n, _ in meshes.values())) == 1, "the three formats hold the same triangles: %s" % meshes)
ply = os.path.join(d, "dev.ply")
r = vk.Run(swarf, program_pocket, ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20",
                                   "--voxel", "0.2", "--mesh", ply, "--design", os.path.join(d, "design2.stl")],
           d, report=False)
if vk.check(r.status == 0 and os.path.exists(ply), "--mesh dev.ply with a design (floor 1 mm above the cut)"):
    _, _, verts = stock_check.read_ply(ply)
    floor = [v for v in verts if abs(v["z"] + 3) < 0.05 and 9 <= v["x"] <= 15 and 8 <= v["y"] <= 12]
    vk.check(len(floor) > 0 and all(abs(v["deviation"] + 1) < 0.02 for v in floor),
             "the floor's vertices: deviation -1 mm (a gouge), %d of them" % len(floor))
    vk.check(all(hue((v["red"], v["green"], v["blue"])) == "blue" for v in floor), "and blue, as in the picture")
# Colours agree with the legend at every voxel size: at
# tolerance 0.25 the legend's range is 1 mm, so the 1 mm gouge or excess of
# the pocket's floor takes the legend's end colour (blue 0.12,0.20,0.75; red
# 0.80,0.10,0.10; the light scales all three channels alike), not a colour
# cut short where the design's narrow band (2 voxels) ended: at 0.1 mm that
# band (0.2 mm) lay inside the tolerance and the floor was drawn green.
for voxel in ("0.2", "0.1"):
    r = vk.Run(swarf, program_pocket, ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20",
                                       "--voxel", voxel], d, report=False)
    if not vk.check(r.status == 0, "the pocket at %s mm" % voxel):
        continue
    grid = os.path.join(d, "pocket%s.vdb" % voxel)
    os.rename(r.out, grid)
    for floor, hi, lo in ((-2, 2, 1), (-4, 0, 1)):  # the channel that leads, and the one that is low
        img = render(grid, "range%s_%d" % (voxel, -floor),
                     ["--view", "top", "--tolerance", "0.25", "--design",
                      os.path.join(d, "design%d.stl" % -floor)])
        c = pixel(img, 12, 10)
        what = "voxel %s, 1 mm %s at tolerance 0.25" % (voxel, "gouge" if floor == -2 else "excess")
        vk.check(c[hi] > 100 and c[lo] < 0.35 * c[hi],
                 "%s: the floor has the legend's end colour (%s, RGB %s)" %
                 (what, "blue" if hi == 2 else "red", c))
# swarf compare against a .vdb design (the uncut box): the pocket is a gouge,
# its volume below the tolerance (0.1 mm) analytic, the same as --design's.
p = subprocess.run([swarf, "compare", pocket, plain], capture_output=True, text=True, timeout=300)
got = dict(l.split("=", 1) for l in p.stdout.splitlines() if "=" in l)
vk.check(p.returncode == 0 and "gouge_mm3" in got, "swarf compare pocket.vdb box.vdb: exit %d" % p.returncode)
if "gouge_mm3" in got:
    vk.near(float(got["gouge_mm3"]), POCKET_AREA * (3 - 0.1), 0.01 * POCKET_AREA * 3,
            "compare: gouge volume = pocket area x (3 mm - tolerance)")
    vk.check(got["gouge_depth_mm"].endswith("(or more)"), "compare: the depth beyond a .vdb design's band says so: %s" %
             got["gouge_depth_mm"])
    vk.near(float(got["excess_mm3"]), 0.0, 1e-9, "compare: no excess")
    r = vk.Run(swarf, program_pocket, ["--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D6,L20",
                                       "--voxel", "0.2", "--design", plain], d)
    dev = r.report["summary"]["design"] if r.report else None
    vk.near(dev and dev["gouge_mm3"], float(got["gouge_mm3"]), 1e-3, "--design box.vdb: the same gouge volume")
    # every feed line cuts into the uncut box: the plunge and the four sides
    # (line 8 the sliver at X6, Y9..11, between the plunge's and line 7's
    # discs, whose voxel centres lie on its surface)
    vk.check(len(r.warnings("mm or more into the design")) == 5,
             "--design box.vdb: each line's gouge at the band says \"or more\" (%d)" %
             len(r.warnings("mm or more into the design")))

# ---- bad input ----------------------------------------------------------------
bad = os.path.join(d, "bad.png")
p = subprocess.run([swarf, "render", pocket, "--image", bad, "--view", "sideways"], capture_output=True, text=True)
vk.check(p.returncode == 2 and not os.path.exists(bad) and "iso" in p.stderr,
         "--view sideways: exit 2 naming the views, no picture (%d: %s)" % (p.returncode, p.stderr.strip()))
vk.check(not stock_check.failures, "the mesh readers' own checks: %s" % stock_check.failures)
sys.exit(vk.done())
