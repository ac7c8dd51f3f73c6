#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""test_python.py -- the Python module `swarf`, as installed, under /usr/bin/python3.

Usage: /usr/bin/python3 test_python.py PREFIX WORKDIR
PREFIX is an installation (install.sh made it): the module is imported from
PREFIX/lib/python3/dist-packages, the command PREFIX/bin/swarf is the reference.

Truth:
  - removed volumes against closed forms: a flat end mill's slot (a stadium
    prism), a ball end mill's trench (half a capsule), per line too (the
    plunge removes a half ball, the feed a half cylinder);
  - the same program through `swarf simulate` gives the same grid, compared
    voxel by voxel with pyopenvdb (an independent reader of both files);
  - files: pyopenvdb reads the .vdb (name, class, voxel size, volume), the STL's
    size and triangle count agree, the PNG has the asked size;
  - alarms, progress, abort, errors with their places, streaming = one shot.
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys

try:
    import numpy as np
    import pyopenvdb as vdb
except ImportError as e:
    sys.exit("test_python.py: %s: install python3-openvdb and python3-numpy" % e)

PREFIX, WORK = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(PREFIX, "lib", "python3", "dist-packages"))
import swarf  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import verifykit as vk  # noqa: E402  (tests/tools: STL designs)

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def near(a, b, rel, what):
    check(abs(a - b) <= rel * abs(b), "%s: %.5f vs %.5f (rel %.2g)" % (what, a, b, rel))


def path(name):
    return os.path.join(WORK, name)


def header_version():
    with open(os.path.join(PREFIX, "include", "swarf", "swarf_version.h")) as f:
        for line in f:
            if line.startswith("#define SWARF_VERSION_STRING"):
                return line.split('"')[1]
    return None


def test_version():
    check(swarf.__version__ == header_version(), "version %s" % swarf.__version__)
    lib = os.path.realpath(swarf._ffi._library_path())
    check(lib.startswith(os.path.realpath(PREFIX)), "library loaded from the prefix: %s" % lib)


SLOT = "G21 G90 G17\nG0 X5 Y5 Z2\nG1 Z-1 F100\nG1 X15\nG0 Z2\nM2\n"


def test_slot():
    fractions = []
    r = swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4,L12"],
                       voxel=0.1, progress=lambda p: fractions.append(p.fraction))
    moves = fractions
    # after every move, the fraction of the text read: the bytes of its lines so far
    want = [len("".join(SLOT.splitlines(True)[:n])) / len(SLOT) for n in (2, 3, 4, 5)]
    check(len(moves) == 4 and all(abs(a - b) < 1e-12 for a, b in zip(moves, want)),
          "progress after each move of text: the fraction of it read %s (lines' bytes %s)"
          % (moves, want))
    near(r.report.volume_before, 20 * 10 * 5, 1e-3, "slot: volume before")
    near(r.removed, 1.0 * (10 * 4 + math.pi * 4), 0.01, "slot: removed = d (L D + pi D^2/4)")
    check(r.report.moves == 4 and r.report.rapids == 2, "slot: %d moves, %d rapids"
          % (r.report.moves, r.report.rapids))
    check(r.report.start == (0, 0, 10), "slot: default start X0 Y0 10 mm above: %s"
          % (r.report.start,))
    near(r.report.path_mm, math.dist(r.report.start, (5, 5, 2)) + 3 + 10 + 3, 1e-9,
         "slot: tip path")
    near(r.stock.volume, r.report.volume_after, 1e-12, "slot: result stock's volume")
    check(r.alarms == [], "slot: no alarms")


# SLOT's cut as a Haas program: the plunge and the pass in a local
# subprogram (M97 P100 calls block N100 of the same program, M99 returns).
HAAS_SLOT = ("%\nO01000\nG21 G90 G17\nG0 X5 Y5 Z2\nM97 P100\nG0 Z2\nM30\n"
             "N100 G1 Z-1 F100\nG1 X15\nM99\n%\n")


def test_dialect():
    kw = dict(stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4,L12"], voxel=0.1)
    a = swarf.simulate(text=SLOT, **kw)
    b = swarf.simulate(text=HAAS_SLOT, dialect="haas", **kw)
    check(b.report.moves == a.report.moves and b.removed == a.removed,
          "haas slot: %d moves, %g mm3 removed (linuxcnc: %d, %g)"
          % (b.report.moves, b.removed, a.report.moves, a.removed))
    # the same cut through a subroutine file on the path
    os.makedirs(path("subs"), exist_ok=True)
    with open(path("subs/slot_pass.ngc"), "w") as f:
        f.write("o<slot_pass> sub\nG1 Z-1 F100\nG1 X15\no<slot_pass> endsub\n")
    c = swarf.simulate(text="G21 G90 G17\nG0 X5 Y5 Z2\no<slot_pass> call\nG0 Z2\nM2\n",
                       subroutine_path=path("nowhere") + ":" + path("subs"), **kw)
    check(c.report.moves == a.report.moves and c.removed == a.removed,
          "subroutine file: %d moves, %g mm3" % (c.report.moves, c.removed))
    try:
        swarf.simulate(text=HAAS_SLOT, **kw)
        check(False, "the Haas program raises under the LinuxCNC dialect (M97)")
    except swarf.InputError as e:
        check(e.line == 5, "linuxcnc refuses M97 at line 5: %s" % (e,))


TRENCH = "G21 G90\nG0 X5 Y6 Z2\nG1 Z-3 F100\nG1 X15\nG0 Z5\nM2\n"


def test_trench_lines():
    seen = []
    opts = dict(text=TRENCH, stock="box:0,0,-10,20,12,0", tools="T1=ball,D6", voxel=0.1)
    r = swarf.simulate(line=seen.append, **opts)
    rr = 3.0
    near(r.removed, math.pi * rr * rr * 10 / 2 + 2 / 3 * math.pi * rr ** 3, 0.01,
         "trench: removed = half capsule")
    lines = {x.line: x for x in r.lines}
    check(sorted(lines) == [2, 3, 4, 5], "trench: lines that moved %s" % sorted(lines))
    check(seen == r.lines, "trench: line callback saw the same results")
    check(all(math.isnan(x.removed) for x in r.lines), "trench: no line volumes unless asked")
    near(lines[4].path_mm, 10, 1e-9, "trench: line 4 path")
    near(lines[4].time_s, 10 / 100 * 60, 1e-9, "trench: line 4 time at F100")
    near(sum(x.path_mm for x in r.lines), r.report.path_mm, 1e-12, "trench: line paths add up")
    r = swarf.simulate(line_volumes=True, **opts)
    lines = {x.line: x for x in r.lines}
    near(lines[3].removed, 2 / 3 * math.pi * rr ** 3, 0.02, "trench: plunge removes a half ball")
    near(lines[4].removed, math.pi * rr * rr * 10 / 2, 0.02,
         "trench: feed removes a half cylinder")
    near(sum(x.removed for x in r.lines), r.removed, 1e-3, "trench: line volumes add up")


def write_program(name, text):
    p = path(name)
    with open(p, "w") as f:
        f.write(text)
    return p


POCKET = ("G21 G90\nT1 M6\nG0 X4 Y4 Z2\nG1 Z-2 F200\nG1 X16\nG2 X16 Y12 I0 J4\nG1 X4\n"
          "G3 X4 Y4 I0 J-4\nG0 Z2\nT2 M6\nG0 X10 Y8\nG1 Z-4 F100\nG1 X12 Y9 Z-3\nG0 Z5\nM2\n")
OPTS = dict(stock="box:0,0,-8,22,16,0", tools=["T1=flat,D3,L15", "T2=ball,D2,L10"], voxel=0.2)


def grid_array(grid, lo, hi):
    arr = np.full(tuple(h - l + 1 for l, h in zip(lo, hi)), np.nan, dtype=np.float32)
    grid.copyToArray(arr, ijk=lo)
    return arr


def test_against_cli():
    prog = write_program("pocket.ngc", POCKET)
    cli_vdb, py_vdb = path("cli.vdb"), path("py.vdb")
    subprocess.run([os.path.join(PREFIX, "bin", "swarf"), "simulate", prog, "--stock",
                    OPTS["stock"], "--tool", OPTS["tools"][0], "--tool", OPTS["tools"][1],
                    "--voxel", str(OPTS["voxel"]), "--out", cli_vdb, "--quiet"], check=True)
    fractions = []
    r = swarf.simulate(prog, progress=lambda p: fractions.append(p.fraction), **OPTS)
    r.write_vdb(py_vdb)
    check(len(fractions) >= r.report.moves, "progress: %d calls for %d moves"
          % (len(fractions), r.report.moves))
    known = [f for f in fractions if f >= 0]  # < 0: not known yet (within the first chunk)
    check(all(f < 0 or f <= 1 for f in fractions) and known == sorted(known) and
          fractions[-1] == 1.0, "progress: fractions unknown or in [0, 1], non-decreasing, "
          "ending at 1: %s" % fractions)
    check(r.report.tool_changes == 2 and r.report.arcs == 2, "pocket: %d tool changes, %d arcs"
          % (r.report.tool_changes, r.report.arcs))

    cli, py = vdb.read(cli_vdb, "stock"), vdb.read(py_vdb, "stock")
    check(py.gridClass == vdb.GridClass.LEVEL_SET, "pyopenvdb: level set")
    check(all(abs(v - 0.2) < 1e-12 for v in py.transform.voxelSize()), "pyopenvdb: voxel 0.2")
    check(py.activeVoxelCount() == cli.activeVoxelCount(), "same active voxels: %d vs %d (CLI)"
          % (py.activeVoxelCount(), cli.activeVoxelCount()))
    blo, bhi = cli.evalActiveVoxelBoundingBox()
    check(py.evalActiveVoxelBoundingBox() == (blo, bhi), "same active bounding box")
    a, b = grid_array(py, blo, bhi), grid_array(cli, blo, bhi)
    check(np.array_equal(a, b), "every voxel equal to the CLI's (max |diff| %g)"
          % float(np.nanmax(np.abs(a - b))))
    # The volume by pyopenvdb's values, the same formula as stock.h's.
    inside = np.clip(0.5 - a.astype(np.float64) / 0.2, 0, 1).sum() * 0.2 ** 3
    near(inside, r.stock.volume, 1e-6, "volume from pyopenvdb's voxels")
    with swarf.Stock.read(cli_vdb) as s:
        check(s.volume == r.stock.volume, "Stock.read(CLI's .vdb).volume is the module's")


def same_grid(a_path, b_path, what):
    a, b = vdb.read(a_path, "stock"), vdb.read(b_path, "stock")
    blo, bhi = b.evalActiveVoxelBoundingBox()
    check(a.activeVoxelCount() == b.activeVoxelCount() and
          a.evalActiveVoxelBoundingBox() == (blo, bhi), "%s: same active voxels (%d)"
          % (what, b.activeVoxelCount()))
    check(np.array_equal(grid_array(a, blo, bhi), grid_array(b, blo, bhi)),
          "%s: every voxel equal to the CLI's" % what)


ROTARY = "G21 G90\nG0 X4 Y0 Z8\nG1 Z4 F200\nG1 A90\nG1 X12 A180\nG0 Z8\nM2\n"


def test_rotary_against_cli():
    prog = write_program("rotary.ngc", ROTARY)
    cli_vdb, py_vdb = path("rotary_cli.vdb"), path("rotary_py.vdb")
    stock, tool = "cylinder:x,5,0,16", "T1=flat,D3"
    subprocess.run([os.path.join(PREFIX, "bin", "swarf"), "simulate", prog, "--machine", "xyza",
                    "--stock", stock, "--tool", tool, "--voxel", "0.25", "--out", cli_vdb,
                    "--quiet"], check=True)
    r = swarf.simulate(prog, stock=stock, tools=tool, voxel=0.25, machine="xyza")
    r.write_vdb(py_vdb)
    near(r.report.volume_before, math.pi * 25 * 16, 0.01, "rotary: the bar's volume")
    # The flat end 1 mm deep into a bar of radius 5 while it turns by 90 degrees,
    # then a helical groove: some material goes, far less than the bar.
    check(5 < r.removed < 0.2 * r.report.volume_before, "rotary: removed %.2f mm^3" % r.removed)
    same_grid(py_vdb, cli_vdb, "xyza")


def test_outputs():
    r = swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4"], voxel=0.25)
    stl, png = path("slot.stl"), path("slot.png")
    n = r.write_stl(stl)
    with open(stl, "rb") as f:
        data = f.read()
    check(n > 0 and len(data) == 84 + 50 * n and struct.unpack("<I", data[80:84])[0] == n,
          "STL: %d triangles, %d bytes" % (n, len(data)))
    r.write_png(png, 160, 120)
    with open(png, "rb") as f:
        head = f.read(24)
    check(head[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", head[16:24]) == (160, 120),
          "PNG 160x120")
    lo, hi = r.stock.bounds  # the band's active voxels reach past the surface
    check(all(l < b + 1e-9 for l, b in zip(lo, (0, 0, -5))) and
          all(h > b - 1e-9 for h, b in zip(hi, (20, 10, 0))), "bounds %s %s" % (lo, hi))
    check(r.stock.sample(10, 5, -0.5) > 0 and r.stock.sample(10, 5, -2) < 0,
          "sample: air in the slot, material below it")
    r.stock.check()
    check(True, "stock.check()")


def test_stock_reuse_and_streaming():
    first = swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4"],
                           voxel=0.2)
    p = path("first.vdb")
    first.write_vdb(p)
    for isolate in (True, False):
        swarf.set_read_isolation(isolate)
        check(swarf.read_isolation() == isolate, "read_isolation %s" % isolate)
        with swarf.Stock.read(p) as s:
            check(s.volume == first.stock.volume, "read back (isolation %s): same volume"
                  % isolate)
    swarf.set_read_isolation(True)
    again = swarf.Stock.read(p)
    # A second program on the first one's result: the slot deepened by 1 mm.
    # It is a fragment (no M2): as a whole program rs274 refuses it at its end.
    deeper = "G0 X5 Y5 Z2\nG1 Z-2 F100\nG1 X15\nG0 Z2\n"
    try:
        swarf.simulate(text=deeper, stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4"])
        check(False, "a whole program with no end is refused")
    except swarf.InputError as e:
        check(e.line == 4 and "program end" in str(e), "no end: refused at line 4: %s" % e)
    r = swarf.simulate(text=deeper, stock=again, tools=["T1=flat,D4"], fragment=True)
    check(again._h is None, "the Stock given to a simulation is the simulation's")
    near(r.removed, 1.0 * (10 * 4 + math.pi * 4), 0.02, "second pass removes the next 1 mm")
    near(r.report.volume_before, first.stock.volume, 1e-12, "second pass starts from the first")
    # Streaming in pieces that split lines = one shot.
    with swarf.Simulation("box:0,0,-5,20,10,0", ["T1=flat,D4"], voxel=0.2) as sim:
        for i in range(0, len(SLOT), 7):
            sim.feed(SLOT[i:i + 7])
        check(sim.report.moves >= 3, "report while streaming: %d moves" % sim.report.moves)
        streamed = sim.finish()
    check(streamed.stock.volume == first.stock.volume, "streamed in 7-byte pieces = one shot")


def test_alarms():
    got = []
    text = "G0 Z5\nG0 X-5 Y5\nG0 Z-1\nG0 X25\nG0 Z5\nM2\n"
    r = swarf.simulate(text=text, stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4"], voxel=0.25,
                       alarm=got.append)
    check(len(r.alarms) >= 1 and r.alarms[0].kind == "rapid" and r.alarms[0].line == 4,
          "rapid through the stock: alarm %s" % r.alarms[:1])
    check(got == r.alarms, "alarm callback saw every alarm")
    check(r.report.alarm_count["rapid"] == len(r.alarms), "report counts %s"
          % r.report.alarm_count)
    near(r.removed, 4 * 1 * 20, 0.03, "the rapid still cuts (a 4 x 1 x 20 mm slot)")


def test_errors():
    try:
        swarf.simulate(text="G0 X0\nG1 X1 F100 Y\n", name="bad.ngc", stock="box:0,0,-1,1,1,0",
                       tools="T1=flat,D1")
        check(False, "bad G-code raises")
    except swarf.InputError as e:
        check(e.file == "bad.ngc" and e.line == 2 and e.column > 0,
              "bad G-code: %s (%s:%d:%d)" % (e, e.file, e.line, e.column))
        check(e.name == "SWARF_ERR_SYNTAX" and str(e).startswith("bad.ngc:2:"),
              "bad G-code: %s, %s" % (e.name, e))
    for opts, what in ((dict(tools="T1=spoon,D3"), "tool"), (dict(stock="box:1,2"), "stock"),
                       (dict(machine="hexapod"), "machine")):
        kw = dict(stock="box:0,0,-1,1,1,0", tools="T1=flat,D1")
        kw.update(opts)
        try:
            swarf.simulate(text="M2\n", **kw)
            check(False, "bad %s spec raises" % what)
        except swarf.InputError as e:
            check(e.message != "", "bad %s: InputError: %s" % (what, e))
    try:  # as the command refuses it
        swarf.simulate(text="M2\n", stock="box:0,0,-5,20,10,0", tools="T1=flat,D1", voxel=6)
        check(False, "a voxel larger than the stock's smallest side raises")
    except swarf.InputError as e:
        check("larger than the stock's smallest side (5 mm)" in str(e), "voxel 6 on a 5 mm stock: %s" % e)
    try:
        swarf.simulate(text="M2\n", stock="box:0,0,-5,20,10,0", tools="T1=flat,D1e100")
        check(False, "an absurd tool diameter raises")
    except swarf.InputError as e:
        check("D: 1e+100 mm is beyond any cutter" in str(e), "tool D1e100: %s" % e)
    try:
        swarf.Stock.read(path("missing.vdb"))
        check(False, "missing .vdb raises")
    except swarf.InputError as e:
        check(e.name == "SWARF_ERR_OPEN", "missing .vdb: %s %s" % (e.name, e))


def test_abort():
    calls = []

    def stop(p):
        calls.append(p.line)
        return len(calls) == 2

    try:
        swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools="T1=flat,D4", voxel=0.25,
                       progress=stop)
        check(False, "progress returning True stops the run")
    except swarf.Aborted as e:
        check(e.name == "SWARF_ERR_ABORTED" and len(calls) == 2, "aborted after 2 calls: %s" % e)

    def boom(p):
        raise KeyError("from the callback")

    try:
        swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools="T1=flat,D4", voxel=0.25,
                       progress=boom)
        check(False, "an exception in a callback propagates")
    except KeyError as e:
        check("from the callback" in str(e), "the callback's own exception: %r" % e)


def test_design():
    """design= and tolerance= against `swarf simulate --design --report` on the
    same job: the same gouge alarms and the same comparison with the design."""
    design, prog, rep = path("design.stl"), write_program("design.ngc", SLOT), path("d.json")
    vk.write_stl(design, vk.box_triangles((0, 0, -5), (20, 10, -0.5)))  # the slot gouges 0.5 mm
    subprocess.run([os.path.join(PREFIX, "bin", "swarf"), "simulate", prog, "--stock",
                    "box:0,0,-5,20,10,0", "--tool", "T1=flat,D4", "--voxel", "0.25", "--design",
                    design, "--tolerance", "0.05", "--report", rep, "--out", path("d.vdb"),
                    "--quiet"], check=True, capture_output=True)
    with open(rep) as f:
        cli = json.load(f)
    r = swarf.simulate(prog, stock="box:0,0,-5,20,10,0", tools="T1=flat,D4", voxel=0.25,
                       design=design, tolerance=0.05)
    d, c = r.report.deviation, cli["summary"]["design"]
    check(d is not None and abs(d.gouge_depth - 0.5) < 0.13, "a gouge of 0.5 mm: %s"
          % (d and d.gouge_depth))
    for got, want, what in ((d.gouge_volume, c["gouge_mm3"], "gouge volume"),
                            (d.excess_volume, c["excess_mm3"], "excess volume"),
                            (d.gouge_depth, c["gouge_depth_mm"], "gouge depth"),
                            (d.excess_height, c["excess_mm"], "excess height")):
        near(got, want, 1e-9, "design: %s as the CLI's" % what)
    gouges = sorted({a.line for a in r.alarms if a.kind == "gouge"})
    check(gouges == sorted({a["line"] for a in cli["alarms"] if a["kind"] == "gouge"}) and gouges,
          "the same gouge lines as the CLI: %s" % gouges)
    # design_cache=: the band kept in the folder, found by the next run; the same comparison
    cache = path("design-cache")
    shutil.rmtree(cache, ignore_errors=True)  # a folder left by an earlier run would count
    runs = [swarf.simulate(prog, stock="box:0,0,-5,20,10,0", tools="T1=flat,D4", voxel=0.25,
                           design=design, tolerance=0.05, design_cache=cache) for _ in range(2)]
    kept = [f for f in os.listdir(cache) if f.endswith(".band")] if os.path.isdir(cache) else []
    check(len(kept) == 1, "design_cache: one band kept in the folder: %s" % kept)
    for k, run in enumerate(runs):
        e = run.report.deviation
        check((e.gouge_volume, e.excess_volume, e.gouge_depth) ==
              (d.gouge_volume, d.excess_volume, d.gouge_depth),
              "design_cache: run %d compares as the run without the cache" % (k + 1))
    try:
        swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools="T1=flat,D4", tolerance=0.1)
        check(False, "tolerance without a design is refused")
    except swarf.InputError as e:
        check("design" in str(e), "tolerance without a design: %s" % e)


def test_numpy():
    """Stock.to_numpy against pyopenvdb's copy of the same grid from the .vdb
    (an independent reader); from_numpy of that array gives the same stock."""
    r = swarf.simulate(text=SLOT, stock="box:0,0,-5,20,10,0", tools=["T1=flat,D4"], voxel=0.25)
    p = path("numpy.vdb")
    r.write_vdb(p)
    a, origin, voxel = r.stock.to_numpy()
    g = vdb.read(p, "stock")
    ijk = g.transform.worldToIndexCellCentered(origin)
    b = np.zeros(a.shape, dtype=np.float32)
    g.copyToArray(b, ijk=ijk)
    check(a.shape == tuple(g.evalActiveVoxelDim()) and np.array_equal(a, b),
          "to_numpy %s = pyopenvdb's copy from %s" % (a.shape, ijk))
    check(abs(voxel - 0.25) < 1e-12 and a.min() < 0 < a.max(), "voxel and signs")
    s = swarf.Stock.from_numpy(a, origin, voxel)
    a2, origin2, _ = s.to_numpy()
    near(s.volume, r.stock.volume, 1e-9, "from_numpy: the same volume")
    check(np.array_equal(a2, a) and np.allclose(origin2, origin), "from_numpy then to_numpy: the same array")
    try:
        swarf.Stock.from_numpy(np.full((4, 4, 4), np.nan), (0, 0, 0), 0.25)
        check(False, "from_numpy refuses NaN")
    except swarf.InputError as e:
        check("not finite" in str(e), "from_numpy refuses NaN: %s" % e)


def test_arguments():
    """wrong types and ranges raise, never crash or wrap."""
    try:
        swarf.Stock(12345678)
        check(False, "Stock(12345678) raises (it segfaulted)")
    except TypeError as e:
        check("Stock.read" in str(e), "Stock(12345678): TypeError: %s" % e)
    kw = dict(text=SLOT, stock="box:0,0,-5,20,10,0", tools="T1=flat,D4", voxel=0.25)
    for bad, exc in ((dict(batch=0), ValueError), (dict(batch=-1), ValueError),
                     (dict(band=2**32 + 3), ValueError), (dict(band=2), ValueError),
                     (dict(band=3.5), TypeError), (dict(voxel=float("nan")), ValueError),
                     (dict(voxel="0.2"), TypeError)):
        args = dict(kw)
        args.update(bad)
        try:
            swarf.simulate(**args)
            check(False, "%s raises %s" % (bad, exc.__name__))
        except exc as e:
            check(True, "%s: %s: %s" % (bad, exc.__name__, e))

    # close() from a progress callback: the run stops, no crash (it segfaulted)
    sim = swarf.Simulation("box:0,0,-5,20,10,0", ["T1=flat,D4"], voxel=0.25,
                           progress=lambda p: sim.close())
    try:
        sim.feed(SLOT)
        sim.finish()
        check(False, "close() in a callback stops the run")
    except swarf.Aborted as e:
        check("closed from a callback" in str(e), "close() in a callback: Aborted: %s" % e)
    try:
        sim.feed("G0 X1\n")
        check(False, "a closed simulation refuses input")
    except ValueError:
        check(True, "a closed simulation refuses input")


# A tool table (T1's G43 length, T2's diameter), a holder that enters the
# top (line 4), a clamp the cutter runs into (line 7): as assembly.sh's job.
ASSEMBLY = ("G21 G90\nT1 M6 G43 H1\nG0 X20 Y20 Z5\nG1 Z-20 F300\nG1 Z-27\nG0 Z30\n"
            "G0 X30 Y20 Z2\nG1 X58\nG0 Z30\nM2\n")


def test_assembly_against_cli():
    prog = write_program("assembly.ngc", ASSEMBLY)
    table = path("tools.tbl")
    with open(table, "w") as f:
        f.write("T1 P1 D6 Z+0 ;flat 6\nT2 P2 D4 Z+12 ;unused\n")
    opts = dict(stock="box:0,0,-40,60,40,0", voxel=0.25, units="mm", tool_table=table,
                tools=["T1=flat,D6,L10,S25"], holders=["T1=20x40"],
                fixtures=["box:50,0,0,60,40,5"])
    report = path("assembly.json")
    cli = subprocess.run([os.path.join(PREFIX, "bin", "swarf"), "simulate", prog, "--stock",
                          opts["stock"], "--voxel", "0.25", "--units", "mm", "--tool-table",
                          table, "--tool", opts["tools"][0], "--holder", opts["holders"][0],
                          "--fixture", opts["fixtures"][0], "--out", path("assembly_cli.vdb"),
                          "--report", report, "--quiet"], capture_output=True, text=True)
    check(cli.returncode == 0, "assembly: the CLI ran: %s" % cli.stderr.strip()[-300:])
    with open(report) as f:
        want = [(a["kind"], a["line"], round(a["depth_mm"], 6)) for a in json.load(f)["alarms"]]
    r = swarf.simulate(prog, line_volumes=True, **opts)
    got = [(a.kind, a.line, round(a.depth, 6)) for a in r.alarms]
    check(got == want and len(got) == 4, "assembly: the CLI's alarms %s, Python's %s"
          % (want, got))
    with open(report) as f:
        cli_lines = json.load(f)["lines"]
    a = r.line_array()
    check(a.dtype.names == ("line", "tool", "moves", "time_s", "path_mm", "removed") and
          list(a["line"]) == [l["line"] for l in cli_lines],
          "line_array: the CLI report's lines %s" % list(a["line"]))
    near(float(a["removed"].sum()), r.removed, 1e-6, "line_array: the lines' volumes add up")
    near(float(a["removed"].sum()), sum(l["removed_mm3"] for l in cli_lines), 1e-9,
         "line_array: the CLI report's volumes")
    r.write_vdb(path("assembly_py.vdb"))
    same_grid(path("assembly_py.vdb"), path("assembly_cli.vdb"), "assembly")
    try:
        swarf.simulate(prog, **dict(opts, tools=["T1=flat,D6", "T1=ball,D6"]))
        check(False, "assembly: a tool given twice is refused")
    except swarf.InputError as e:
        check("twice" in str(e), "assembly: a tool given twice: %s" % e)
    try:
        swarf.simulate(prog, **dict(opts, tool_table=path("none.tbl")))
        check(False, "assembly: a missing tool table is refused")
    except swarf.InputError as e:
        check("none.tbl" in str(e), "assembly: a missing tool table: %s" % e)


def main():
    os.makedirs(WORK, exist_ok=True)
    for t in (test_version, test_slot, test_trench_lines, test_against_cli,
              test_rotary_against_cli, test_outputs,
              test_stock_reuse_and_streaming, test_alarms, test_errors, test_abort,
              test_dialect, test_design, test_numpy, test_arguments,
              test_assembly_against_cli):
        print("--", t.__name__)
        try:
            t()
        except Exception as e:  # a crash in one test is a failure, not the end
            import traceback
            traceback.print_exc()
            check(False, "%s raised %r" % (t.__name__, e))
    print("%d failed" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
