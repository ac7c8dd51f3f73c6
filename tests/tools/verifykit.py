# SPDX-License-Identifier: MPL-2.0
"""verifykit.py -- helpers of the verification tests (machine setup, design
comparison, report): run `swarf simulate`, read its JSON report with Python's
own json module, read its grid with pyopenvdb, write designs as STL.

Every check prints one line ("ok ..." or "FAIL ..."); done() returns the
exit status.
"""
import json
import math
import os
import struct
import subprocess
import tempfile
import zlib

_failures = []
_passed = [0]


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if cond:
        _passed[0] += 1
    else:
        _failures.append(what)
    return cond


def near(got, want, tol, what):
    ok = got is not None and want is not None and abs(got - want) <= tol
    return check(ok, "%s: %s vs %s (tol %g)" % (what, got, want, tol))


def done():
    print("%d passed, %d failed" % (_passed[0], len(_failures)))
    return 1 if _failures else 0


class Run:
    """One `swarf simulate` run: status, stdout, stderr, report (parsed)."""

    def __init__(self, swarf, program, args, workdir, report=True, name="p.ngc"):
        self.dir = workdir
        self.program = os.path.join(workdir, name)
        with open(self.program, "w") as f:
            f.write(program)
        self.out = os.path.join(workdir, "out.vdb")
        self.json = os.path.join(workdir, "report.json")
        for p in (self.out, self.json):
            if os.path.exists(p):
                os.unlink(p)
        cmd = [swarf, "simulate", self.program, "--out", self.out] + list(args)
        if report:
            cmd += ["--report", self.json]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        self.status, self.stdout, self.stderr = p.returncode, p.stdout, p.stderr
        self.report = None
        if report and os.path.exists(self.json):
            with open(self.json) as f:
                self.report = json.load(f)

    def removed(self):
        return self.report["summary"]["removed_mm3"] if self.report else None

    def lines(self):
        """line -> sum of removed_mm3 over its tools (from the report)."""
        out = {}
        for e in self.report["lines"]:
            out[e["line"]] = out.get(e["line"], 0.0) + e["removed_mm3"]
        return out

    def warnings(self, word):
        return [l for l in self.stderr.splitlines() if word in l]


def grid_volume(path):
    """The volume of the level set in a .vdb (pyopenvdb and numpy): voxel^3
    times the sum of each voxel's inside fraction clamp(1/2 - value / voxel)."""
    import numpy as np
    import pyopenvdb as vdb
    g = vdb.read(path, "stock")
    vox = g.transform.voxelSize()[0]
    lo, hi = g.evalActiveVoxelBoundingBox()
    arr = np.empty(tuple(h - l + 1 for l, h in zip(lo, hi)), dtype=np.float32)
    arr.fill(g.background)
    g.copyToArray(arr, ijk=lo)
    return float(np.clip(0.5 - arr.astype(np.float64) / vox, 0, 1).sum() * vox ** 3)


def workdir():
    return tempfile.mkdtemp(prefix="swarf_verify_")


# ---- designs as STL (binary, outward normals, counter-clockwise) -----------


def box_triangles(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tris = []
    for a, b, c, d in faces:
        tris += [(v[a], v[b], v[c]), (v[a], v[c], v[d])]
    return tris


def quad(a, b, c, d):
    return [(a, b, c), (a, c, d)]


def pocket_box_triangles(lo, hi, plo, phi, floor):
    """A box lo..hi with a rectangular pocket plo..phi (x, y) open at the top
    (z = hi[2]) down to z = floor: a closed, oriented mesh."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    px0, py0 = plo
    px1, py1 = phi
    tris = []
    # bottom and sides of the outer box (not the top)
    for t in box_triangles(lo, hi):
        if not all(p[2] == z1 for p in t):
            tris.append(t)
    # the top: a frame around the pocket (normals up)
    T = lambda x, y: (x, y, z1)
    tris += quad(T(x0, y0), T(x1, y0), T(px1, py0), T(px0, py0))
    tris += quad(T(x1, y0), T(x1, y1), T(px1, py1), T(px1, py0))
    tris += quad(T(x1, y1), T(x0, y1), T(px0, py1), T(px1, py1))
    tris += quad(T(x0, y1), T(x0, y0), T(px0, py0), T(px0, py1))
    # the pocket's walls (normals into the pocket) and floor (normal up)
    B = lambda x, y: (x, y, floor)
    tris += quad(T(px0, py0), T(px1, py0), B(px1, py0), B(px0, py0))
    tris += quad(T(px1, py0), T(px1, py1), B(px1, py1), B(px1, py0))
    tris += quad(T(px1, py1), T(px0, py1), B(px0, py1), B(px1, py1))
    tris += quad(T(px0, py1), T(px0, py0), B(px0, py0), B(px0, py1))
    tris += quad(B(px0, py0), B(px1, py0), B(px1, py1), B(px0, py1))
    return tris


def normal(t):
    a, b, c = t
    u = [b[i] - a[i] for i in range(3)]
    w = [c[i] - a[i] for i in range(3)]
    n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    l = math.sqrt(sum(x * x for x in n)) or 1.0
    return [x / l for x in n]


def write_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"swarf test design".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(t)))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def mesh_volume(tris):
    """Enclosed volume of a closed oriented mesh (divergence theorem)."""
    v = 0.0
    for a, b, c in tris:
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
              a[2] * (b[0] * c[1] - b[1] * c[0]))
    return v / 6.0


def read_png(path):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB or RGBA PNG."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    at, idat, w = 8, b"", None
    while at < len(data):
        n, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + n]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[at + 8 + n:at + 12 + n])[0]:
            raise ValueError("bad CRC in " + kind.decode())
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, (depth, ctype, interlace)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows
