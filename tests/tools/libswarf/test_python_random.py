#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""test_python_random.py -- the Python module under random calls and arguments.

Usage: /usr/bin/python3 test_python_random.py PREFIX WORKDIR [TRIALS [SEED]]

A property test: swarf.simulate, Simulation (its methods in random order,
callbacks that raise, stop or close it) and Stock are called with arguments
drawn from good values and from wrong types, absurd ranges, NaN, huge
integers, bytes, strings with NUL and non-ASCII characters. Every call must
return, or raise one of the documented exceptions (swarf.SwarfError and its
InputError, TypeError, ValueError, OverflowError); any other exception, a
crash or a hang fails. A good call checks what it returned (a Result with a
finite volume no larger than the stock's). The trials are drawn from SEED
(default fixed): a failure prints the trial to rerun alone.
"""
import math
import os
import random
import sys

PREFIX, WORK = sys.argv[1], sys.argv[2]
TRIALS = int(sys.argv[3]) if len(sys.argv) > 3 else 600
SEED = int(sys.argv[4]) if len(sys.argv) > 4 else 20261206
sys.path.insert(0, os.path.join(PREFIX, "lib", "python3", "dist-packages"))
import swarf  # noqa: E402



class CallbackError(Exception):
    """Raised by a test callback: the module passes it on to the caller."""


ALLOWED = (swarf.SwarfError, TypeError, ValueError, OverflowError, CallbackError)
STOCK = "box:0,0,-4,12,8,0"
PROGRAMS = [
    "G21 G90\nG0 X2 Y2 Z2\nG1 Z-1 F200\nG1 X10\nG0 Z2\nM2\n",
    "G21 G90 G17\nG0 X6 Y4 Z1\nG2 X6 Y4 I2 Z-1 P2 F300\nG0 Z2\nM2\n",
    "%\nO1000\nG21 G90\nG0 X2 Y2 Z2\nG1 Z-1 F100\nG1 X9\nM30\n%\n",
    "G21 G90\nG0 X2 Y2 Z2\nG83 X6 Y4 Z-3 R1 Q1 F100\nG80\nM2\n",
    "G21\n#1=0\no1 while [#1 lt 3]\nG1 X[#1*3] Y2 Z-1 F200\n#1=[#1+1]\no1 endwhile\nM2\n",
    "G21 G0 X1\n",  # no end
    "G1 X1 Y\nM2\n",  # bad word
    "",
]
ODD = [None, 0, -1, 1, 3, 2 ** 31, 2 ** 63, 2 ** 64 + 3, -2 ** 63, 0.5, 1e-300, 1e300,
       float("nan"), float("inf"), -float("inf"), "", "abc", "\x00", "caf\u00e9", b"bytes",
       [], [1, 2, 3], (1, 2), {}, object(), True, 3 + 4j, "T1=flat,D4", STOCK]


def program(r):
    p = r.choice(PROGRAMS)
    if p and r.random() < 0.3:  # a mutation: a character changed, cut or repeated
        i = r.randrange(len(p))
        p = r.choice([p[:i] + r.choice("0X.-#[%\n ") + p[i + 1:], p[:i], p + p[i:]])
    return p


def maybe(r, good, odd=0.25):
    return r.choice(ODD) if r.random() < odd else good


def kwargs(r):
    kw = {}
    choices = {
        "voxel": lambda: r.choice([0.5, 0.8, 1.0]),
        "band": lambda: r.choice([3, 4]),
        "batch": lambda: r.choice([1, 16, 1024]),
        "start": lambda: (0, 0, 10),
        "g54": lambda: (0, 0, 0),
        "units": lambda: r.choice(["mm", "in"]),
        "dialect": lambda: r.choice(["linuxcnc", "fanuc", "haas", "grbl"]),
        "block_delete": lambda: r.choice([True, False]),
        "fragment": lambda: r.choice([True, False]),
        "machine": lambda: r.choice(["xyz", "xyza,pivot=0,0"]),
        "line_volumes": lambda: r.choice([True, False]),
    }
    for name, good in choices.items():
        if r.random() < 0.35:
            kw[name] = maybe(r, good())
    if "voxel" not in kw or not isinstance(kw.get("voxel"), float) or not kw["voxel"] >= 0.5:
        kw.setdefault("voxel", 0.5)
    return kw


def callback(r, box):
    kind = r.randrange(5)
    if kind == 0:
        return None
    if kind == 1:
        return lambda *a: True  # stop
    if kind == 2:
        def boom(*a):
            raise CallbackError("from a callback")
        return boom
    if kind == 3:
        return lambda *a: box[0].close() if box[0] is not None else None
    return lambda *a: None


def check_result(res, what):
    vol = res.stock.volume
    # the grid's volume of the 12 x 8 x 4 mm box is within a voxel's layer of 384 mm^3
    if not (math.isfinite(vol) and vol <= 12 * 8 * 4 * 1.25 and res.removed >= -1e-6):
        raise AssertionError("%s: a result out of range: volume %r removed %r" % (what, vol, res.removed))


def trial_simulate(r):
    box = [None]
    kw = kwargs(r)
    res = swarf.simulate(text=maybe(r, program(r), 0.15), stock=maybe(r, STOCK, 0.15),
                         tools=maybe(r, r.choice(["T1=flat,D4", ["T1=ball,D3"]]), 0.15),
                         progress=callback(r, box), alarm=callback(r, box), line=callback(r, box),
                         **kw)
    check_result(res, "simulate")


def trial_handle(r):
    box = [None]
    kw = kwargs(r)
    sim = swarf.Simulation(maybe(r, STOCK, 0.1), maybe(r, ["T1=flat,D4"], 0.1),
                           progress=callback(r, box), **kw)
    box[0] = sim
    try:
        for _ in range(r.randrange(1, 6)):
            op = r.randrange(6)
            try:
                if op <= 1:
                    sim.feed(maybe(r, program(r), 0.2))
                elif op == 2:
                    sim.feed_file(maybe(r, os.path.join(WORK, "p.ngc"), 0.3))
                elif op == 3:
                    sim.report
                elif op == 4:
                    res = sim.finish()
                    check_result(res, "finish")
                else:
                    sim.close()
            except ALLOWED:
                pass
    finally:
        sim.close()


def trial_stock(r):
    path = maybe(r, os.path.join(WORK, "s.vdb"), 0.5)
    with swarf.Stock.read(path) as s:
        for _ in range(r.randrange(1, 4)):
            op = r.randrange(4)
            if op == 0:
                s.sample(maybe(r, 1.0), maybe(r, 1.0), maybe(r, -1.0))
            elif op == 1:
                s.write_png(os.path.join(WORK, "s.png"), maybe(r, 64), maybe(r, 48))
            elif op == 2:
                assert math.isfinite(s.volume)
            else:
                s.close()


def main():
    os.makedirs(WORK, exist_ok=True)
    with open(os.path.join(WORK, "p.ngc"), "w") as f:
        f.write(PROGRAMS[0])
    swarf.simulate(text=PROGRAMS[0], stock=STOCK, tools="T1=flat,D4", voxel=0.5).write_vdb(
        os.path.join(WORK, "s.vdb"))
    bad, raised, fine = [], 0, 0
    for t in range(TRIALS):
        r = random.Random(SEED * 1000003 + t)
        kind = r.choice([trial_simulate, trial_simulate, trial_handle, trial_stock])
        try:
            kind(r)
            fine += 1
        except ALLOWED:
            raised += 1
        except Exception as e:  # not a documented exception: the property fails
            bad.append("trial %d (%s): %s: %s" % (t, kind.__name__, type(e).__name__, e))
    for b in bad[:20]:
        print("FAIL", b)
    print("%d trials (seed %d): %d returned, %d raised a documented error, %d broke the rules"
          % (TRIALS, SEED, fine, raised, len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
