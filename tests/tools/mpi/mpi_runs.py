#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""mpi_runs.py SWARF FIXTURES MPIRUN -- `swarf simulate` under mpirun.

Each case runs one process (no launcher) and then `mpirun --oversubscribe -n
2` and `-n 3` with the same command line, and checks that the written grids
are the same voxel for voxel (pyopenvdb, same_grid.py: max difference 0,
same active topology, same leaves), that the summaries agree line for line
(but for wall times) and that the warnings (alarms) are the same lines. The
programs are in the tree (a plain clone runs every case):
  demo      fixtures/demo.ngc at 0.5 mm, two tools, and a rapid move that
            cuts material at its end;
  rotary    a 5-axis program of our own on xyzac-trt (A tilts, C turns; a
            ball end mill grooving a cylinder through the table's rotation);
  alarms    the demo's pocket and the first part of its ball-end work on a
            tool whose shank enters the material (collisions, depths measured
            by bisection), a rapid through material, and a design the moves
            gouge (per-move gouges, per-line volumes in the JSON report,
            compared field for field but for times).
Then the failures: bad G-code under mpirun (one message, exit status 2,
nothing written), an output folder that does not exist (the same), and a
rank killed mid-run (non-zero exit, the previous output intact).
Exits 77 (skipped) when mpirun is missing or swarf was built without MPI.
"""
import hashlib
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import verifykit as vk  # noqa: E402

swarf, fixtures, mpirun = sys.argv[1], sys.argv[2], sys.argv[3]
if mpirun == "NO-MPI":
    print("SKIP: swarf was built without MPI (SWARF_MPI OFF: no libopenmpi-dev at configure)")
    sys.exit(77)
if not shutil.which(mpirun):
    print("SKIP: mpirun (%s) not found: install openmpi-bin (tools/run does)" % mpirun)
    sys.exit(77)
here = os.path.dirname(os.path.abspath(__file__))
d = vk.workdir()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_btl="self,vader", OMPI_MCA_rmaps_base_oversubscribe="1")
TIMEOUT = 600  # a hang limit, not a timing


def run(n, args, tag=None, wait=True):
    cmd = ([swarf] if n == 1 else [mpirun, "--oversubscribe", "-n", str(n), swarf]) + ["simulate"] + args
    e = dict(env, SWARF_MPI_TEST_TAG=tag) if tag else env
    if not wait:
        return subprocess.Popen(cmd, env=e, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)
    p = subprocess.run(cmd, env=e, capture_output=True, text=True, timeout=TIMEOUT)
    return p


TIMED = re.compile(r"^\s*(simulation |collision check|design read |wrote )")


def summary(text):
    return [l for l in text.splitlines() if not TIMED.match(l)]


def ours(text):
    """swarf's own lines on stderr (not mpirun's notices)."""
    return [l for l in text.splitlines()
            if l.startswith("swarf") or re.match(r"^\S+:\d+:(\d+:)? ", l)]


def same_grid(a, b, what):
    p = subprocess.run(["/usr/bin/python3", os.path.join(here, "same_grid.py"), a, b],
                       capture_output=True, text=True, timeout=TIMEOUT)
    print("  " + p.stdout.strip().replace("\n", "\n  "))
    vk.check(p.returncode == 0, what + ": grids identical voxel for voxel")


def untimed(report):
    """The JSON report without its wall and CPU times."""
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items()
                    if k not in ("seconds", "wall_s", "collision_s", "simulation_s", "total_s",
                                 "moves_per_s")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x
    return strip(report)


def case(name, args, report=False):
    ref = None
    for n in (1, 2, 3):
        out = os.path.join(d, "%s-%d.vdb" % (name, n))
        extra = ["--report", os.path.join(d, "%s-%d.json" % (name, n))] if report else []
        p = run(n, args + ["--out", out] + extra)
        vk.check(p.returncode == 0, "%s -n %d: exit 0 (%s)" % (name, n, p.stderr.strip()[-300:]))
        got = (summary(p.stdout), ours(p.stderr))
        if n == 1:
            ref = got
            print("%s: %s" % (name, " | ".join(got[0][1:4])))
            print("  %d warning lines" % len(got[1]))
            continue
        same_grid(os.path.join(d, "%s-1.vdb" % name), out, "%s -n %d" % (name, n))
        vk.check(got[0] == ref[0], "%s -n %d: the same summary%s" % (
            name, n, "" if got[0] == ref[0] else ":\n%s\nvs\n%s" % (got[0], ref[0])))
        vk.check(got[1] == ref[1], "%s -n %d: the same warning lines (%d)%s" % (
            name, n, len(ref[1]), "" if got[1] == ref[1] else ":\n%s\nvs\n%s" % (got[1][:5], ref[1][:5])))
        if report:
            with open(os.path.join(d, "%s-1.json" % name)) as f:
                a = untimed(json.load(f))
            with open(os.path.join(d, "%s-%d.json" % (name, n))) as f:
                b = untimed(json.load(f))
            vk.check(a == b, "%s -n %d: the same JSON report but for times" % (name, n))
    return ref


with open(os.path.join(fixtures, "demo.ngc")) as f:
    demo_lines = [l for l in f if l.strip() not in ("M30", "%")]
demo = os.path.join(d, "demo.ngc")
with open(demo, "w") as g:
    g.writelines(demo_lines)
    g.write("G0 Z5\nG0 X40 Y30\nG0 Z-4\nG0 X60\nG0 Z20\nM30\n")
DEMO = ["--stock", "box:0,0,-20,80,60,0", "--tool", "T1=flat,D6,L24", "--tool",
        "T2=ball,D3.175,L20", "--voxel", "0.5"]
ref = case("demo", [demo] + DEMO)
vk.check(any("rapid" in l for l in ref[1]), "demo: its rapid move through material is warned")

rot = os.path.join(d, "rotary.ngc")
with open(rot, "w") as g:
    g.write("G21 G90 G94\nG0 X24 Y0 Z40 A0 C0\nG1 Z26 F600\n")
    for i in range(1, 145):
        g.write("G1 X%.3f Z%.3f A%.3f C%.3f F1500\n" % (
            20.5 + 0.01 * i, 26 - 0.02 * i, 12 * math.sin(i / 9.0), 5 * i))
    g.write("G0 Z60\nM30\n")
case("rotary", [rot, "--machine", "xyzac-trt", "--stock", "cylinder:z,42,0,30",
                "--tool", "T1=ball,D4,L30", "--voxel", "0.5"])

prog = os.path.join(d, "alarms.ngc")
with open(prog, "w") as g:
    g.writelines(demo_lines[:1200])
    g.write("G0 Z5\nG0 X10 Y50\nG1 Z-8 F300\nG1 X70\nG0 Z-6 X40 Y55\nG0 Z20\nM30\n")
design = os.path.join(d, "design.stl")
vk.write_stl(design, vk.box_triangles((2, 2, -20), (78, 58, -2.5)))
ALARMS = [prog, "--stock", "box:0,0,-20,80,60,0", "--tool", "T1=flat,D6,L24",
          "--tool", "T2=ball,D3.175,L6,S12,N3.175",
          "--voxel", "0.5", "--design", design, "--collision-depths", "20"]
ref = case("alarms", ALARMS, report=True)
kinds = " ".join(ref[1])
vk.check("rapid" in kinds and "shank" in kinds and "gouge" in kinds,
         "alarms: rapid, shank and gouge warnings all present")
# without --report each part measures the gouges only: the same warnings
p = run(2, ALARMS + ["--out", os.path.join(d, "alarms-gouges.vdb")])
vk.check(p.returncode == 0 and ours(p.stderr) == ref[1],
         "alarms -n 2 without --report (gouges only): the same warning lines%s" % (
             "" if ours(p.stderr) == ref[1] else ":\n%s\nvs\n%s" % (ours(p.stderr)[:5], ref[1][:5])))
same_grid(os.path.join(d, "alarms-1.vdb"), os.path.join(d, "alarms-gouges.vdb"),
          "alarms -n 2 without --report")

# ---- failures ----------------------------------------------------------------
bad = os.path.join(d, "bad.ngc")
with open(bad, "w") as f:
    f.write("G21 G0 Z5\nG1 X10 F100\nG1 X20 Q\n")
for n in (1, 2, 3):
    out = os.path.join(d, "bad-%d.vdb" % n)
    p = run(n, [bad, "--stock", "box:0,0,-10,40,30,0", "--tool", "T1=ball,D3", "--voxel", "0.5",
                "--out", out])
    msgs = [l for l in ours(p.stderr) if "bad.ngc:3:" in l]
    vk.check(p.returncode == 2, "bad G-code -n %d: exit status 2 (got %d)" % (n, p.returncode))
    vk.check(len(msgs) == 1, "bad G-code -n %d: one message (%s)" % (n, msgs))
    vk.check(not os.path.exists(out), "bad G-code -n %d: nothing written" % n)
    if n == 1:
        ref_msg = msgs
    else:
        vk.check(msgs == ref_msg, "bad G-code -n %d: the one-process message" % n)
p = run(2, [bad, "--stock", "box:0,0,-10,40,30,0", "--tool", "T1=ball,D3",
            "--out", os.path.join(d, "no", "such", "out.vdb")])
vk.check(p.returncode == 2 and len([l for l in ours(p.stderr) if "--out" in l]) == 1,
         "an unwritable --out under mpirun: one message, exit 2")

# Ranks given different inputs: the same command in two folders
# whose p.ngc differ (mpirun's MPMD form, --wdir each). Every rank hashes its
# command line and input files and compares with rank 0's before any work: a
# refusal naming the rank and the program, nothing written (before, the ranks
# cut their parts with different programs and wrote the mixture, exit 0).
for sub, extra in (("wa", ""), ("wb", "G1 X30 Y20\n")):
    os.makedirs(os.path.join(d, sub), exist_ok=True)
    with open(os.path.join(d, sub, "p.ngc"), "w") as f:
        f.write("G21 G90 G0 Z5\nG0 X5 Y5\nG1 Z-2 F300\nG1 X20\n" + extra + "G0 Z5\nM2\n")
mixed = os.path.join(d, "mixed.vdb")
job = [swarf, "simulate", "p.ngc", "--stock", "box:0,0,-10,40,30,0", "--tool", "T1=flat,D4",
       "--voxel", "0.5", "--out", mixed]
p = subprocess.run([mpirun, "--oversubscribe", "-n", "1", "--wdir", os.path.join(d, "wa")] + job +
                   [":", "-n", "1", "--wdir", os.path.join(d, "wb")] + job,
                   env=env, capture_output=True, text=True, timeout=TIMEOUT)
vk.check(p.returncode != 0 and "rank 1 of 2 was given a different program" in p.stderr and
         not os.path.exists(mixed),
         "ranks with different programs: refused before any work (exit %d): %s" %
         (p.returncode, [l for l in ours(p.stderr)][:2]))

# A rank killed mid-run, over an existing output. The job is a long raster
# of full-depth slots (a few MB of G-code); rank 1 is killed once it is seen,
# while stopped (SIGSTOP), reading that program past its first chunk and
# before its end: mid-run by construction, however fast the machine.
out = os.path.join(d, "demo-1.vdb")
with open(out, "rb") as f:
    before = hashlib.sha256(f.read()).hexdigest()
longprog = os.path.join(d, "long.ngc")
with open(longprog, "w") as f:
    f.write("G21 G90 G0 Z5\nG0 X-5 Y0\nG1 Z-8 F1000\n")
    for i in range(120000):
        y = (i % 400) * 0.2
        f.write("G1 X%s Y%.1f\nG1 Y%.1f\n" % ("85" if i % 2 == 0 else "-5", y, y + 0.1))
    f.write("G0 Z5\nM30\n")
size = os.path.getsize(longprog)
tag = "swarf-mpi-test-%d" % os.getpid()
proc = run(2, [longprog, "--stock", "box:0,0,-20,80,80,0", "--tool", "T1=flat,D6,L30",
               "--voxel", "0.25", "--quiet", "--out", out], tag=tag, wait=False)


def rank_pid(rank):
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open("/proc/%s/environ" % pid, "rb") as f:
                e = f.read().split(b"\0")
        except OSError:
            continue
        if (b"SWARF_MPI_TEST_TAG=" + tag.encode()) in e and \
                ("OMPI_COMM_WORLD_RANK=%d" % rank).encode() in e:
            return int(pid)
    return None


def reading_at(pid, path):
    """The offsets of pid's open descriptors on path."""
    at = []
    try:
        for fd in os.listdir("/proc/%d/fd" % pid):
            try:
                if os.readlink("/proc/%d/fd/%s" % (pid, fd)) != path:
                    continue
                with open("/proc/%d/fdinfo/%s" % (pid, fd)) as f:
                    at += [int(l.split()[1]) for l in f if l.startswith("pos:")]
            except OSError:
                continue
    except OSError:
        pass
    return at


victim, killed, t0 = None, False, time.time()
while not killed and time.time() - t0 < TIMEOUT and proc.poll() is None:
    victim = victim or rank_pid(1)
    if victim is None:
        time.sleep(0.01)
        continue
    try:
        os.kill(victim, signal.SIGSTOP)
    except ProcessLookupError:
        break
    if any(128 * 1024 <= a < size for a in reading_at(victim, os.path.realpath(longprog))):
        os.kill(victim, signal.SIGKILL)
        killed = True
    else:
        os.kill(victim, signal.SIGCONT)
        time.sleep(0.01)
_, err = proc.communicate(timeout=TIMEOUT)
vk.check(killed, "a rank was found and killed mid-run")
vk.check(proc.returncode != 0, "a killed rank: mpirun exits non-zero (%d)" % proc.returncode)
with open(out, "rb") as f:
    vk.check(hashlib.sha256(f.read()).hexdigest() == before, "a killed rank: the output is intact")
vk.check(not [x for x in os.listdir(d) if x.startswith("demo-1.vdb.") or ".tmp" in x],
         "a killed rank: no temporary file left")
rc = vk.done()
shutil.rmtree(d, ignore_errors=True)
sys.exit(rc)
