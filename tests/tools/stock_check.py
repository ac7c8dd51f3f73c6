#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""stock_check.py -- independent readers and makers for tests/tools/stock_io.sh.

  box-stl PATH XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX [good|open|nonmanifold|flipped|empty] [ascii]
      write a box as an STL (outward triangles), damaged as asked
  fog-vdb PATH     write a .vdb holding one float grid that is not a level set
  other-vdb SRC.vdb PATH
      write SRC's stock grid as another tool might: after a fog volume, named "part"
  same A.vdb B.vdb TOL_MM
      pyopenvdb: the two grids' values agree within TOL_MM over both narrow bands
  sample A.vdb X,Y,Z:SIGN ...
      pyopenvdb: the value at each world point has the sign given (+ or -)
  volume A.vdb EXPECTED TOL_MM3
      pyopenvdb + numpy: the enclosed volume (inside fractions) is EXPECTED
  mesh FILE EXPECTED_VOLUME REL_TOL [dev Z VALUE TOL]
      parse FILE (.ply binary, .obj, .stl binary) with this script's own
      parser: every edge is shared by two triangles in opposite directions,
      the enclosed volume is EXPECTED_VOLUME; with dev: vertices at height Z
      carry the deviation VALUE (PLY) and a red colour
  ply-dev FILE.ply Z VALUE TOL
      the "deviation" of the vertices at height Z is VALUE (within TOL)
  png FILE legend|view-top|view-front
      decode the PNG (zlib, filter bytes) and check what the picture shows
Exit status 0 when every check holds; failures are printed.
"""
import struct
import sys
import zlib

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def box_stl(path, spec, damage="good", ascii=""):
    lo = [float(v) for v in spec.split(",")[:3]]
    hi = [float(v) for v in spec.split(",")[3:]]
    faces = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
    corner = lambda i: [hi[k] if (i >> k) & 1 else lo[k] for k in range(3)]
    tris = []
    for f in faces:
        tris.append([corner(f[0]), corner(f[1]), corner(f[2])])
        tris.append([corner(f[0]), corner(f[2]), corner(f[3])])
    if damage == "open":
        tris.pop()
    elif damage == "nonmanifold":
        tris.append(list(tris[0]))
    elif damage == "flipped":
        tris[0] = [tris[0][0], tris[0][2], tris[0][1]]
    elif damage == "empty":
        tris = []
    if ascii:
        with open(path, "w") as out:
            out.write("solid box\n")
            for t in tris:
                out.write(" facet normal 0 0 0\n  outer loop\n")
                for v in t:
                    out.write("   vertex %r %r %r\n" % tuple(v))
                out.write("  endloop\n endfacet\n")
            out.write("endsolid box\n")
        return
    with open(path, "wb") as out:
        out.write(b"box".ljust(80, b"\0") + struct.pack("<I", len(tris)))
        for t in tris:
            out.write(struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0))


def fog_vdb(path):
    import pyopenvdb as vdb
    g = vdb.FloatGrid()
    g.name = "density"
    g.gridClass = vdb.GridClass.FOG_VOLUME
    g.getAccessor().setValueOn((1, 2, 3), 0.5)
    vdb.write(path, grids=[g])


def other_tool_vdb(src, path):
    """Write src's stock as another tool would: a fog volume named "density"
    first, then the level set under the name "part"."""
    import pyopenvdb as vdb
    g = vdb.read(src, "stock")
    g.name = "part"
    fog = vdb.FloatGrid()
    fog.name = "density"
    fog.gridClass = vdb.GridClass.FOG_VOLUME
    fog.getAccessor().setValueOn((1, 2, 3), 0.5)
    vdb.write(path, grids=[fog, g])


def read_grid(path):
    import pyopenvdb as vdb
    names = [m.name for m in vdb.readAllGridMetadata(path)]
    return vdb.read(path, "stock" if "stock" in names else names[0])


def dense(grid, lo, hi):
    import numpy as np
    arr = np.full(tuple(int(h - l + 1) for l, h in zip(lo, hi)), grid.background, dtype=np.float32)
    grid.copyToArray(arr, ijk=tuple(int(v) for v in lo))
    return arr


def same(a, b, tol):
    import numpy as np
    ga, gb = read_grid(a), read_grid(b)
    va, vb = ga.transform.voxelSize()[0], gb.transform.voxelSize()[0]
    check(abs(va - vb) < 1e-12, "same voxel %g %g" % (va, vb))
    # index boxes in a's index space (b's origin may differ by whole voxels)
    oa = ga.transform.indexToWorld((0, 0, 0))
    ob = gb.transform.indexToWorld((0, 0, 0))
    shift = [round((ob[k] - oa[k]) / va) for k in range(3)]
    check(all(abs((ob[k] - oa[k]) / va - shift[k]) < 1e-6 for k in range(3)), "lattices coincide")
    (alo, ahi), (blo, bhi) = ga.evalActiveVoxelBoundingBox(), gb.evalActiveVoxelBoundingBox()
    blo = [blo[k] + shift[k] for k in range(3)]
    bhi = [bhi[k] + shift[k] for k in range(3)]
    lo = [min(alo[k], blo[k]) - 1 for k in range(3)]
    hi = [max(ahi[k], bhi[k]) + 1 for k in range(3)]
    da = dense(ga, lo, hi)
    db = dense(gb, [lo[k] - shift[k] for k in range(3)], [hi[k] - shift[k] for k in range(3)])
    band = min(ga.background, gb.background)
    near = (np.abs(da) < band) | (np.abs(db) < band)
    diff = float(np.max(np.abs(np.clip(da, -band, band) - np.clip(db, -band, band))[near])) if near.any() else 0.0
    check(diff <= tol, "max |A - B| over the bands %.3g mm (tolerance %g)" % (diff, tol))


def sample(a, points):
    g = read_grid(a)
    acc = g.getConstAccessor()
    for xyz, sign in points:
        p = [float(v) for v in xyz.split(",")]
        ijk = g.transform.worldToIndexCellCentered(tuple(p))
        v = acc.getValue(ijk)
        check(v < 0 if sign == "-" else v > 0, "value at %s is %s: %.4f" % (xyz, sign, v))


def volume(a, expected, tol):
    import numpy as np
    g = read_grid(a)
    v = g.transform.voxelSize()[0]
    lo, hi = g.evalActiveVoxelBoundingBox()
    d = dense(g, [l - 1 for l in lo], [h + 1 for h in hi]).astype(np.float64)
    vol = float(np.clip(0.5 - d / v, 0.0, 1.0).sum()) * v ** 3
    check(abs(vol - expected) <= tol, "volume %.3f mm^3, expected %.3f (+-%g)" % (vol, expected, tol))


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    check(header[0] == "ply" and header[1] == "format binary_little_endian 1.0", "PLY header")
    nv = nf = 0
    props = []
    element = None
    for line in header:
        w = line.split()
        if w[:1] == ["element"]:
            element = w[1]
            if element == "vertex":
                nv = int(w[2])
            else:
                nf = int(w[2])
        elif w[:1] == ["property"] and element == "vertex":
            props.append((w[1], w[2]))
    fmt = "<" + "".join({"float": "f", "uchar": "B"}[t] for t, _ in props)
    size = struct.calcsize(fmt)
    names = [n for _, n in props]
    verts = []
    at = end
    for _ in range(nv):
        verts.append(dict(zip(names, struct.unpack_from(fmt, data, at))))
        at += size
    tris = []
    for _ in range(nf):
        n = data[at]
        tris.append(struct.unpack_from("<%dI" % n, data, at + 1))
        at += 1 + 4 * n
    check(at == len(data), "PLY size matches its header")
    return [(v["x"], v["y"], v["z"]) for v in verts], tris, verts


def read_obj(path):
    pts, tris = [], []
    for line in open(path):
        w = line.split()
        if w[:1] == ["v"]:
            pts.append(tuple(float(x) for x in w[1:4]))
        elif w[:1] == ["f"]:
            tris.append(tuple(int(x.split("/")[0]) - 1 for x in w[1:]))
    return pts, tris, None


def read_stl(path):
    data = open(path, "rb").read()
    n = struct.unpack_from("<I", data, 80)[0]
    check(len(data) == 84 + 50 * n, "binary STL size")
    pts, tris, index = [], [], {}
    for t in range(n):
        rec = struct.unpack_from("<12f", data, 84 + 50 * t)
        tri = []
        for c in range(3):
            p = rec[3 + 3 * c: 6 + 3 * c]
            if p not in index:
                index[p] = len(pts)
                pts.append(p)
            tri.append(index[p])
        tris.append(tuple(tri))
    return pts, tris, None


def mesh(path, expected, rel, dev=None):
    reader = {"ply": read_ply, "obj": read_obj, "stl": read_stl}[path.rsplit(".", 1)[1].lower()]
    pts, tris, verts = reader(path)
    edges = {}
    vol = 0.0
    for t in tris:
        check(len(t) == 3, "triangles only") if len(t) != 3 else None
        for i in range(3):
            e = (t[i], t[(i + 1) % 3])
            edges[e] = edges.get(e, 0) + 1
        a, b, c = (pts[i] for i in t)
        vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
    bad = sum(1 for e, n in edges.items() if n != 1 or edges.get((e[1], e[0]), 0) != 1)
    check(bad == 0, "%s: %d triangles, every edge twice, opposite ways (%d bad)" % (path, len(tris), bad))
    check(abs(vol - expected) <= rel * abs(expected), "enclosed volume %.3f, expected %.3f" % (vol, expected))
    if dev is not None:
        z, value, tol = dev
        top = [v for v in verts if abs(v["z"] - z) < 1e-3]
        check(len(top) > 0, "vertices at z=%g" % z)
        worst = max(abs(v["deviation"] - value) for v in top)
        check(worst <= tol, "deviation at z=%g: %g within %g (worst %.4f)" % (z, value, tol, worst))
        red = sum(1 for v in top if v["red"] > 180 and v["green"] < 80 and v["blue"] < 80)
        check(red == len(top), "those vertices are red (%d of %d)" % (red, len(top)))


def ply_dev(path, z, value, tol):
    """The deviation of a PLY's vertices at height z (only, not the mesh's topology)."""
    pts, tris, verts = read_ply(path)
    top = [v for v in verts if abs(v["z"] - z) < 1e-3]
    check(len(top) > 0, "vertices at z=%g" % z)
    worst = max(abs(v["deviation"] - value) for v in top) if top else 1e30
    check(worst <= tol, "deviation at z=%g: %g within %g (worst %.4f)" % (z, value, tol, worst))


def read_png(path):
    data = open(path, "rb").read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n", "PNG signature")
    at, idat, w = 8, b"", 0
    while at < len(data):
        n, kind = struct.unpack_from(">I4s", data, at)
        body = data[at + 8: at + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack_from(">IIBB", body)
            check(depth == 8 and colour == 2, "8-bit RGB")
        elif kind == b"IDAT":
            idat += body
        at += 12 + n
    raw = zlib.decompress(idat)
    rows = []
    for y in range(h):
        line = raw[y * (3 * w + 1): (y + 1) * (3 * w + 1)]
        check(line[0] == 0, "filter 0") if line[0] != 0 else None
        rows.append(line[1:])
    pixel = lambda x, y: tuple(rows[y][3 * x: 3 * x + 3])
    return w, h, pixel


def png(path, what):
    w, h, px = read_png(path)
    if what == "legend":
        strip = [px(x, y) for x in range(int(0.85 * w), w) for y in range(h)]
        red = any(r > 180 and g < 60 and b < 60 for r, g, b in strip)
        blue = any(b > 150 and r < 60 and g < 80 for r, g, b in strip)
        green = any(g > 150 and r < 100 and b < 120 for r, g, b in strip)
        check(red and blue and green, "legend bar: red %s, green %s, blue %s" % (red, green, blue))
        body = [px(x, y) for x in range(0, int(0.8 * w), 4) for y in range(0, h, 4)]
        check(any(r > 180 and g < 60 and b < 60 for r, g, b in body), "excess (red) on the part")
    else:  # a stock whose +X half is lower (a step), seen from the top or front
        bg = px(2, 2)
        def is_bg(p):
            return all(abs(p[k] - bg[k]) <= 12 for k in range(3))
        if what == "view-top":  # the whole block is seen: left and right are stock
            check(not is_bg(px(int(0.2 * w), h // 2)) and not is_bg(px(int(0.8 * w), h // 2)), "top: stock across")
            check(px(int(0.2 * w), h // 2) != px(int(0.8 * w), h // 2), "top: two floors differ")
        else:  # front: X right, Z up: the high part at the left
            check(not is_bg(px(int(0.2 * w), int(0.25 * h))), "front: high part on the left")
            check(is_bg(px(int(0.8 * w), int(0.25 * h))), "front: above the low part is background")
            check(not is_bg(px(int(0.8 * w), int(0.75 * h))), "front: low part on the right")


def main(argv):
    cmd = argv[1]
    if cmd == "box-stl":
        box_stl(*argv[2:])
        return 0
    if cmd == "fog-vdb":
        fog_vdb(argv[2])
        return 0
    if cmd == "other-vdb":
        other_tool_vdb(argv[2], argv[3])
        return 0
    if cmd == "same":
        same(argv[2], argv[3], float(argv[4]))
    elif cmd == "sample":
        sample(argv[2], [tuple(a.rsplit(":", 1)) for a in argv[3:]])
    elif cmd == "volume":
        volume(argv[2], float(argv[3]), float(argv[4]))
    elif cmd == "mesh":
        dev = (float(argv[6]), float(argv[7]), float(argv[8])) if len(argv) > 5 and argv[5] == "dev" else None
        mesh(argv[2], float(argv[3]), float(argv[4]), dev)
    elif cmd == "ply-dev":
        ply_dev(argv[2], float(argv[3]), float(argv[4]), float(argv[5]))
    elif cmd == "png":
        png(argv[2], argv[3])
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
