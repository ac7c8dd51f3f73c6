#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""readme_tour.py SRC SWARF PREFIX WORK -- the README's tour runs as written.

Every indented block of README.md that starts with `build/tools/swarf` is run
(its continuation lines joined) in WORK, where `fixtures` is the tree's and
`build/tools/swarf` the command under test; each file it names after --out,
--mesh, --image, --report or --html must then exist and be non-empty, and
the report must be JSON with the per-line records. The Python block (`import
swarf`) runs with the module installed under PREFIX, and the C example
(`#include <stdio.h>`) is built with pkg-config against PREFIX and run. Blocks with `...` are
templates (Modbus, MPI: their own tests run them) and are listed, not run.
"""
import glob
import json
import os
import re
import shlex
import shutil
import subprocess
import sys

SRC, SWARF, PREFIX, WORK = (os.path.abspath(a) for a in sys.argv[1:5])
OUTPUT_FLAGS = ("--out", "--mesh", "--image", "--report", "--html")


def blocks(text):
    """The README's indented code blocks, each a list of lines (indent removed;
    blank lines inside a block kept, as Markdown keeps them)."""
    out, cur = [], []
    for line in text.splitlines():
        if line.startswith("    "):
            cur.append(line[4:])
        elif cur and line.strip() == "":
            cur.append("")
        elif cur:
            out.append(cur)
            cur = []
    if cur:
        out.append(cur)
    return [[l for l in b] for b in (strip_blank(b) for b in out) if b]


def strip_blank(b):
    while b and b[-1] == "":
        b = b[:-1]
    return b


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def run_command(block):
    cmd = " ".join(l.rstrip("\\").strip() for l in block)
    cmd = re.sub(r"\s+#.*$", "", cmd)
    argv = shlex.split(cmd)
    print("$ " + cmd)
    r = subprocess.run(argv, cwd=WORK, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        fail("exit %d: %s" % (r.returncode, r.stderr.strip()[-2000:]))
    for i, a in enumerate(argv[:-1]):
        if a in OUTPUT_FLAGS:
            path = os.path.join(WORK, argv[i + 1])
            if not os.path.isfile(path) or os.path.getsize(path) == 0:
                fail("%s %s was not written" % (a, argv[i + 1]))
            if a == "--report":
                with open(path) as f:
                    rep = json.load(f)
                if not rep.get("lines"):
                    fail("the report %s has no per-line records" % argv[i + 1])
    return argv


def run_c(block):
    """The C example: built against the installed library with pkg-config
    (PREFIX's swarf.pc only) and run where fixtures/ is."""
    pc = os.path.join(PREFIX, "lib", "pkgconfig")
    if not os.path.isdir(pc):
        pc = glob.glob(os.path.join(PREFIX, "lib*", "*", "pkgconfig"))[0]
    src, exe = os.path.join(WORK, "demo.c"), os.path.join(WORK, "demo")
    with open(src, "w") as f:
        f.write("\n".join(block) + "\n")
    env = dict(os.environ, PKG_CONFIG_LIBDIR=pc)
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "swarf"], env=env,
                           capture_output=True, text=True, check=True).stdout.split()
    libdir = [f[2:] for f in flags if f.startswith("-L")]
    r = subprocess.run(["cc", "-std=c11", "-Wall", "-Werror", src, "-o", exe] + flags +
                       ["-Wl,-rpath," + libdir[0]], capture_output=True, text=True)
    if r.returncode != 0:
        fail("the C example does not build: %s" % r.stderr[-2000:])
    print("$ cc demo.c $(pkg-config --cflags --libs swarf) -o demo && ./demo")
    r = subprocess.run([exe], cwd=WORK, capture_output=True, text=True, timeout=600)
    if r.returncode != 0 or not r.stdout.startswith("removed "):
        fail("the C example: exit %d: %s %s" % (r.returncode, r.stdout, r.stderr[-1000:]))
    print(r.stdout.strip())
    return float(r.stdout.split()[1])


def run_python(block):
    pydir = os.path.join(PREFIX, "lib", "python3", "dist-packages")
    if not os.path.isdir(os.path.join(pydir, "swarf")):
        fail("the Python module is not installed under %s" % PREFIX)
    env = dict(os.environ, PYTHONPATH=pydir)
    print(">>> " + "\n... ".join(block))
    r = subprocess.run(["/usr/bin/python3", "-c", "\n".join(block)], cwd=WORK, env=env,
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        fail("the Python example: %s" % r.stderr.strip()[-2000:])
    for name in ("remaining.vdb", "remaining.png"):
        if os.path.getsize(os.path.join(WORK, name)) == 0:
            fail("the Python example wrote an empty %s" % name)


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(os.path.join(WORK, "build", "tools"))
    os.symlink(os.path.join(SRC, "fixtures"), os.path.join(WORK, "fixtures"))
    os.symlink(os.path.abspath(SWARF), os.path.join(WORK, "build", "tools", "swarf"))
    with open(os.path.join(SRC, "README.md")) as f:
        text = f.read()
    ran = templates = 0
    for b in blocks(text):
        if b[0].startswith("build/tools/swarf"):
            if any("..." in l for l in b):
                print("template, not run: " + b[0])
                templates += 1
                continue
            run_command(b)
            ran += 1
        elif b[0].startswith("import swarf"):
            run_python(b)
            ran += 1
        elif b[0].startswith("#include <stdio.h>"):
            removed = run_c(b)
            if not 1000 < removed < 80 * 60 * 20:
                fail("the C example removed %g mm^3" % removed)
            ran += 1
    if ran < 5:
        fail("only %d runnable tour blocks found in README.md" % ran)
    print("README tour: %d blocks ran, %d templates" % (ran, templates))


main()
