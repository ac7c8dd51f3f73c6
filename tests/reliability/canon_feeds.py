#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""canon_feeds.py SWARF PROGRAM EXPECTED TOOLS: G93 F0 against LinuxCNC's rs274.

EXPECTED is `rs274 -t TOOLS -g PROGRAM` (made once by hand with Debian's
linuxcnc-uspace, see README). For every motion call (STRAIGHT_FEED, ARC_FEED)
swarf's canon must give the same numbers (1e-4) and the same feed rate in
force (the last SET_FEED_RATE before it): rs274 floors an inverse-time rate at
0.1 units/min, for lines and arcs alike, so no feed move has F 0.
"""
import re
import subprocess
import sys

CALL = re.compile(r"^\s*\d+\s+N\S*\s+([A-Z_]+)\((.*)\)\s*$")


def motions(text):
    feed, out = None, []
    for line in text.splitlines():
        m = CALL.match(line)
        if not m:
            continue
        name, args = m.group(1), m.group(2)
        if name == "SET_FEED_RATE":
            feed = float(args)
        elif name in ("STRAIGHT_FEED", "ARC_FEED"):
            out.append((name, [float(a) for a in args.split(",")], feed))
    return out


def main():
    swarf, program, expected, tools = sys.argv[1:5]
    run = subprocess.run([swarf, "parse", "--canon", "--tools", tools, program],
                         capture_output=True, text=True, timeout=60)
    if run.returncode != 0:
        sys.exit("swarf parse failed (%d): %s" % (run.returncode, run.stderr))
    got = motions(run.stdout)
    want = motions(open(expected).read())
    if len(got) != len(want):
        sys.exit("%d motion calls, rs274 has %d" % (len(got), len(want)))
    for i, (g, w) in enumerate(zip(got, want)):
        if g[0] != w[0] or any(abs(a - b) > 1e-4 for a, b in zip(g[1], w[1])):
            sys.exit("call %d: %s%s, rs274 %s%s" % (i, g[0], g[1], w[0], w[1]))
        if g[2] is None or abs(g[2] - w[2]) > 1e-4 or not g[2] > 0:
            sys.exit("call %d (%s): feed %s, rs274 %s" % (i, g[0], g[2], w[2]))
    print("ok: %d motion calls, feeds as rs274's (smallest %g)" %
          (len(got), min(g[2] for g in got)))


main()
