#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""html.py SWARF [REAL] -- `swarf simulate --html` opened in a real browser.

With REAL (the corpus folder ../shared/conformance/real), the size check
instead: bear at 0.2 mm (a 1/8" ball, 15,159 moves) makes a page under
30 MB whose mesh was coarsened to about 500,000 triangles (SKIPPED without
the corpus).

A slot through the top of a box whose design lies 2 mm lower (the rest of
the top face is excess), with a rapid through the stock (an alarm), written
as a page; headless Chromium (Debian's, WebGL on SwiftShader) loads it from
disk with no network. Checked against what the test knows independently:
  - the page is one file with no http(s) reference, under 30 MB;
  - <body> gets data-ready="1", data-triangles equal to the face count in the
    header of the PLY the page embeds, data-lines equal to the number of
    program lines with moves that `swarf parse` lists;
  - the alarm list links the rapid's line; no console error;
  - the deviation legend's scale: -4, -1, 0, 1, 4 tolerances (half a voxel);
  - used as a person would (the page's #check=X,Y,Z mode clicks the canvas
    where a world point appears, then the first alarm's link): a click on
    the slot's floor names line 4 (the G1 that cut it; the slider goes
    there), one on the untouched top names none; the alarm's link moves the
    slider to line 7, where the tool (one piece: no shank or holder given)
    stands at the rapid's end point X15 Y3 Z-1; the chart has ink; each
    standard view's button turns the camera to look along its direction;
  - a screenshot shows the part (pixels off the background) and the excess
    colour (saturated red, from the design comparison).
SKIPPED (77) without chromium.
"""
import base64
import os
import re
import shutil
import subprocess
import sys
import tempfile

import verifykit as vk
from verifykit import check

swarf = sys.argv[1]
if len(sys.argv) > 2:  # the size on bear at 0.2 mm
    bear = os.path.join(sys.argv[2], "camotics-bear.nc")
    if not os.path.exists(bear):
        print("SKIPPED: no corpus at %s (../shared/conformance/real)" % sys.argv[2])
        sys.exit(77)
    with tempfile.TemporaryDirectory() as d:
        page = os.path.join(d, "bear.html")
        p = subprocess.run([swarf, "simulate", bear, "--stock", "box:0,0,-20,80,80,0", "--tool",
                            "T1=ball,D3.175,L25.4", "--voxel", "0.2", "--quiet", "--out",
                            os.path.join(d, "bear.vdb"), "--html", page],
                           capture_output=True, text=True, timeout=600)
        size = os.path.getsize(page) if os.path.exists(page) else 0
        tri = re.search(rb"element face (\d+)", base64.b64decode(re.search(
            r'<script id="swarf-mesh" type="application/octet-stream">([^<]*)</script>',
            open(page).read()).group(1).replace("\n", "")[:400])) if size else None
        ok = p.returncode == 0 and 0 < size < 30e6 and tri and int(tri.group(1)) < 650000
        print("%s bear at 0.2 mm: %.1f MB, %s triangles (exit %d)" % (
            "ok  " if ok else "FAIL", size / 1e6, tri.group(1).decode() if tri else "?",
            p.returncode))
        sys.exit(0 if ok else 1)
chromium = shutil.which("chromium") or shutil.which("chromium-browser")
if chromium is None:
    print("SKIPPED: chromium is not installed (apt-get install chromium)")
    sys.exit(77)
FLAGS = ["--headless", "--no-sandbox", "--use-gl=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-gpu-sandbox", "--allow-file-access-from-files", "--no-first-run",
         "--disable-background-networking", "--virtual-time-budget=15000"]
d = tempfile.mkdtemp()
try:
    prog = os.path.join(d, "slot.ngc")
    with open(prog, "w") as f:
        f.write("G21 G90\nG0 X-5 Y10 Z5\nG1 Z-2 F300\nG1 X35\nG0 Z5\nG0 X15 Y3\nG0 Z-1\n"
                "G0 Z5\nG2 X15 Y17 I0 J7 F400\nM2\n")
    design = os.path.join(d, "design.stl")
    vk.write_stl(design, vk.box_triangles((0, 0, -5), (30, 20, -2)))
    page = os.path.join(d, "page.html")
    p = subprocess.run([swarf, "simulate", prog, "--stock", "box:0,0,-5,30,20,0", "--tool",
                        "T1=flat,D6,L10", "--voxel", "0.25", "--design", design, "--out",
                        os.path.join(d, "out.vdb"), "--html", page, "--quiet"],
                       capture_output=True, text=True, timeout=300)
    check(p.returncode == 0 and os.path.exists(page), "simulate --html: exit %d %s"
          % (p.returncode, p.stderr[-300:]))
    text = open(page, encoding="utf-8").read()
    check(len(text) < 30e6 and not re.search(r"(src|href)=\"?https?:", text),
          "one file, no network reference (%.1f MB)" % (len(text) / 1e6))
    mesh = re.search(r'<script id="swarf-mesh" type="application/octet-stream">([^<]*)</script>',
                     text)
    ply = base64.b64decode(mesh.group(1)) if mesh else b""
    faces = re.search(rb"element face (\d+)", ply)
    want_tri = int(faces.group(1)) if faces else -1
    listed = subprocess.run([swarf, "parse", prog], capture_output=True, text=True).stdout
    want_lines = len({l.split()[0] for l in listed.splitlines()
                      if l.split()[1] in ("RAPID", "LINE", "ARC")})
    log = os.path.join(d, "chrome.log")
    with open(log, "w") as err:
        dom = subprocess.run([chromium] + FLAGS + ["--enable-logging=stderr", "--v=0",
                             "--dump-dom", "file://" + page], stdout=subprocess.PIPE,
                             stderr=err, text=True, timeout=120).stdout
    body = re.search(r"<body([^>]*)>", dom)
    attrs = dict(re.findall(r'data-(\w+)="([^"]*)"', body.group(1))) if body else {}
    check(attrs.get("ready") == "1", "the page is ready in the browser: %s" % attrs)
    check(want_tri > 0 and attrs.get("triangles") == str(want_tri),
          "data-triangles %s = the embedded PLY's %d faces" % (attrs.get("triangles"), want_tri))
    check(attrs.get("lines") == str(want_lines),
          "data-lines %s = swarf parse's %d lines with moves" % (attrs.get("lines"), want_lines))
    check(re.search(r'<a href="#">line 7: rapid', dom) is not None,
          "the alarm list links the rapid at line 7")
    scale = re.findall(r'<span style="left:[0-9.]+%?">([^<]*)</span>', dom)
    check(scale == ["-0.5 gouge", "-0.125", "0", "0.125", "0.5 excess"] and 'id="legend"' in dom,
          "the deviation legend: %s" % scale)

    def used(point):
        out = subprocess.run([chromium] + FLAGS + ["--dump-dom", "file://%s#check=%s" % (page, point)],
                             capture_output=True, text=True, timeout=120).stdout
        b = re.search(r"<body([^>]*)>", out)
        return dict(re.findall(r'data-(\w+)="([^"]*)"', b.group(1))) if b else {}
    floor = used("15,11.5,-2;25,17,0")
    check(floor.get("pick") == "4;0" and floor.get("pickshown") == "4",
          "a click on the slot's floor names line 4 and shows it, one on the untouched top "
          "none: %s" % floor)
    check(floor.get("alarm") == "7" and floor.get("tool") == "1" and
          floor.get("toolat") == "15.000,3.000,-1.000",
          "the alarm's link shows line 7, the tool at X15 Y3 Z-1: %s" % floor)
    check(int(floor.get("chart", "0")) > 200, "the chart has ink: %s pixels" % floor.get("chart"))
    check(floor.get("views") == "iso,top,front,right,left",
          "each view button looks along its direction: %s" % floor.get("views"))
    console = [l for l in open(log, errors="replace") if "CONSOLE" in l or "Uncaught" in l]
    check(not [l for l in console if "rror" in l or "Uncaught" in l],
          "no console error (%s)" % console[:3])
    shot = os.path.join(d, "shot.png")
    subprocess.run([chromium] + FLAGS + ["--window-size=1000,700", "--screenshot=" + shot,
                   "file://" + page], capture_output=True, timeout=120, cwd=d)
    if not os.path.exists(shot):
        check(False, "a screenshot")
    else:
        w, h, rows = vk.read_png(shot)
        view = [px for row in rows for px in row[:w - 340]]  # the 3D view, left of the panel
        part = sum(1 for r, g, b in view if abs(r - 244) + abs(g - 244) + abs(b - 242) > 30)
        red = sum(1 for r, g, b in view if r > 170 and g < 110 and b < 110)
        check(part > 0.05 * len(view), "the part fills the view: %d of %d pixels" % (part, len(view)))
        check(red > 0.01 * len(view), "the excess colour shows: %d red pixels" % red)
finally:
    shutil.rmtree(d, ignore_errors=True)
sys.exit(vk.done())
