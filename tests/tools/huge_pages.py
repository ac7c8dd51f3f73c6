#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""huge_pages.py SWARF -- the command runs malloc on transparent huge pages
(tools/cli/main.c: it executes itself once more with
GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which glibc reads only at start-up).

Seen from a child, which inherits the command's environment: SWARF_VDB_READER
names a script that writes its environment to a file and fails, and
`swarf info x.vdb` runs it. Then:
- without GLIBC_TUNABLES the child sees glibc.malloc.hugetlb=1 (and the
  command ended: it executed itself once, not in a loop);
- with SWARF_HUGEPAGES=0 it sees no GLIBC_TUNABLES;
- a caller's own GLIBC_TUNABLES reaches it unchanged;
- the outcome (exit status 2, the reader's failure named) is the same each time.
And by the dynamic loader's own account (LD_DEBUG=files names each program it
starts): `info` starts twice, `parse`, `envelope` and `--help` once (they make
no grid, and the restart would cost them more than it saves).
"""
import os
import shutil
import subprocess
import sys
import tempfile

from verifykit import check, done

swarf = sys.argv[1]
d = tempfile.mkdtemp(prefix="swarf_huge_pages_")
script = os.path.join(d, "reader.sh")
with open(script, "w") as f:
    f.write('#!/bin/sh\nenv > "$HUGE_PAGES_ENV"\nexit 1\n')
os.chmod(script, 0o755)
with open(os.path.join(d, "x.vdb"), "w") as f:
    f.write("not read\n")


def child_env(tag, **extra):
    """The reader child's environment under a run of `swarf info` with the
    caller's environment less GLIBC_TUNABLES and SWARF_HUGEPAGES, plus extra."""
    env = {k: v for k, v in os.environ.items() if k not in ("GLIBC_TUNABLES", "SWARF_HUGEPAGES")}
    out = os.path.join(d, tag + ".env")
    env.update(SWARF_VDB_READER=script, HUGE_PAGES_ENV=out, **extra)
    p = subprocess.run([swarf, "info", "x.vdb"], cwd=d, env=env, capture_output=True, text=True,
                       timeout=60)
    check(p.returncode == 2 and "the reader failed" in p.stderr,
          "%s: exit 2, the reader's failure named (%d: %s)" % (tag, p.returncode, p.stderr.strip()))
    seen = {}
    if os.path.exists(out):
        for line in open(out):
            k, _, v = line.rstrip("\n").partition("=")
            seen[k] = v
    check(bool(seen), "%s: the reader ran" % tag)
    return seen


seen = child_env("default")
check(seen.get("GLIBC_TUNABLES") == "glibc.malloc.hugetlb=1",
      "default: the command runs with glibc.malloc.hugetlb=1 (%s)" % seen.get("GLIBC_TUNABLES"))
seen = child_env("off", SWARF_HUGEPAGES="0")
check("GLIBC_TUNABLES" not in seen, "SWARF_HUGEPAGES=0: no tunable set (%s)" % seen.get("GLIBC_TUNABLES"))
seen = child_env("caller's", GLIBC_TUNABLES="glibc.malloc.arena_max=2")
check(seen.get("GLIBC_TUNABLES") == "glibc.malloc.arena_max=2",
      "a caller's GLIBC_TUNABLES is kept as it is (%s)" % seen.get("GLIBC_TUNABLES"))


def starts(*args):
    """How many times the loader started swarf itself for `swarf args`."""
    env = {k: v for k, v in os.environ.items() if k not in ("GLIBC_TUNABLES", "SWARF_HUGEPAGES")}
    env.update(LD_DEBUG="files", SWARF_VDB_READER=script, HUGE_PAGES_ENV=os.path.join(d, "x.env"))
    p = subprocess.run([swarf] + list(args), cwd=d, env=env, capture_output=True, text=True,
                       timeout=60)
    name = os.path.basename(swarf)
    return sum(1 for line in p.stderr.splitlines()
               if "transferring control:" in line and
               os.path.basename(line.split("transferring control:")[1].strip()) == name)


with open(os.path.join(d, "p.ngc"), "w") as f:
    f.write("G21 G90\nG1 X1 F100\nM2\n")
check(starts("info", "x.vdb") == 2, "info: started twice (restarted with the tunable)")
for args in (["parse", "p.ngc"], ["--help"], ["envelope", "--help"]):
    n = starts(*args)
    check(n == 1, "%s: started once, no restart (%d)" % (" ".join(args), n))
shutil.rmtree(d, ignore_errors=True)
sys.exit(done())
