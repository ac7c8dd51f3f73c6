#!/usr/bin/python3
# SPDX-License-Identifier: MPL-2.0
"""modbus_spin.py SWARF -- the Modbus servers never spin.

- TCP out of descriptors: swarf runs under a limit of 48 open files, and 80
  clients connect and stay; once accept fails (EMFILE) the connection stays
  queued and select says "readable" at once: the server spun a core. Now
  the listener rests 0.2 s: over 2 s the process uses < 5 % of a core.
- RTU line lost: the pty pair (socat) is killed under a serving swarf;
  every read failed at once and the loop spun (61 % of a core measured).
  Now the line is reopened with backoff: < 5 % over 2 s.
CPU time is swarf's own (utime + stime in /proc/PID/stat), not wall time:
a busy machine does not change it. Missing socat fails the test.
"""
import os
import re
import resource
import shutil
import socket
import subprocess
import sys
import tempfile
import time

swarf = sys.argv[1]
failures = 0
TICK = os.sysconf("SC_CLK_TCK")


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures += 1


def cpu_s(pid):
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICK  # utime, stime


def wait_for(path, regex, proc, timeout=30):
    end = time.time() + timeout
    while time.time() < end and proc.poll() is None:
        with open(path) as f:
            m = re.search(regex, f.read())
        if m:
            return m
        time.sleep(0.02)
    return None


def run(work, extra, limit_files=None):
    prog = os.path.join(work, "p.ngc")
    with open(prog, "w") as f:
        f.write("G21 G90\nG0 Z5\nG0 X5 Y5\nG1 Z-2 F300\nG1 X15\nG0 Z5\nM2\n")
    err = open(os.path.join(work, "stderr"), "w")

    def limit():
        if limit_files:
            resource.setrlimit(resource.RLIMIT_NOFILE, (limit_files, limit_files))

    return subprocess.Popen([swarf, "simulate", prog, "--stock", "box:0,0,-5,20,20,0", "--tool",
                             "T1=flat,D3", "--voxel", "0.5", "--out", os.path.join(work, "r.vdb"),
                             "--quiet", "--modbus-linger", "6"] + extra,
                            stdout=subprocess.DEVNULL, stderr=err, preexec_fn=limit), err.name


def idle_share(pid, seconds=2.0):
    a = cpu_s(pid)
    time.sleep(seconds)
    return (cpu_s(pid) - a) / seconds


with tempfile.TemporaryDirectory() as work:
    proc, err = run(work, ["--modbus", "tcp:127.0.0.1:0"], limit_files=48)
    m = wait_for(err, r"Modbus TCP server on [^ ]*:(\d+)", proc)
    check(m is not None, "TCP: the server started under 48 open files")
    # The flood comes once the run is over and its outputs are written (the
    # server lingers 6 s): out of descriptors, a run could not write them, and
    # a sanitizer could not read the process's maps (a false report).
    end = time.time() + 60
    while m and not os.path.exists(os.path.join(work, "r.vdb")) and time.time() < end:
        time.sleep(0.02)
    if m:
        port = int(m.group(1))
        clients = []
        for _ in range(80):
            s = socket.socket()
            s.settimeout(2)
            try:
                s.connect(("127.0.0.1", port))
            except OSError:
                pass
            clients.append(s)
        time.sleep(0.5)
        share = idle_share(proc.pid)
        check(share < 0.05, "TCP out of descriptors: %.1f %% of a core over 2 s (< 5 %%)" %
              (100 * share))
        for s in clients:
            s.close()
    proc.wait(30)

    if shutil.which("socat") is None:
        check(False, "socat is missing: apt-get install socat (or tools/run test)")
    else:
        line, client = os.path.join(work, "line"), os.path.join(work, "client")
        socat = subprocess.Popen(["socat", "pty,raw,echo=0,link=" + line,
                                  "pty,raw,echo=0,link=" + client], stderr=subprocess.DEVNULL)
        for _ in range(100):
            if os.path.exists(line) and os.path.exists(client):
                break
            time.sleep(0.05)
        proc, err = run(work, ["--modbus", "rtu:%s,19200,N,8,1,unit=3" % line])
        check(wait_for(err, r"Modbus RTU server on", proc) is not None, "RTU: the server started")
        time.sleep(0.5)
        socat.kill()  # the line is lost
        socat.wait()
        time.sleep(0.5)
        if proc.poll() is None:
            share = idle_share(proc.pid)
            check(share < 0.05, "RTU line lost: %.1f %% of a core over 2 s (< 5 %%)" % (100 * share))
        proc.wait(30)
        check(proc.returncode == 0, "RTU: the run ends normally (exit %d)" % proc.returncode)
print("%d failed" % failures)
sys.exit(1 if failures else 0)
