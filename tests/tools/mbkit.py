# SPDX-License-Identifier: MPL-2.0
"""mbkit.py -- helpers shared by the Modbus tests of `swarf simulate`.

Starts swarf with a --modbus option on a port it picks itself (port 0; the
port is read back from swarf's announcement on stderr), decodes the register
map tools/doc/modbus.md documents, reads the summary swarf prints, and talks raw
Modbus TCP for the frames a well-behaved client library would never send.
Nothing here knows swarf's internals: only its command line, its output and
the documented map.
"""
import atexit
import os
import re
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time

def require(*programs):
    """Fail loudly (never skip) when a test helper is missing."""
    missing = [p for p in programs if shutil.which(p) is None]
    try:
        import pymodbus  # noqa: F401
        import pymodbus.client  # noqa: F401
    except ImportError as e:
        missing.append("python3-pymodbus (%s)" % e)
    if missing:
        print("FAIL missing test helpers: %s; install them: apt-get install python3-pymodbus "
              "python3-serial-asyncio mbpoll socat (or run tools/run test)" % ", ".join(missing))
        sys.exit(1)


DEMO = ["--stock", "box:0,0,-20,80,60,0", "--tool", "T1=flat,D6,L24",
        "--tool", "T2=ball,D3.175,L20"]


class Failures:
    """Collects checks; exit status 1 if any failed."""

    def __init__(self):
        self.passed = 0
        self.failed = 0

    def check(self, name, cond, detail=""):
        if cond:
            self.passed += 1
        else:
            self.failed += 1
            print("FAIL %s %s" % (name, detail), flush=True)

    def finish(self):
        print("%d passed, %d failed" % (self.passed, self.failed), flush=True)
        sys.exit(1 if self.failed else 0)


class Swarf:
    """A `swarf simulate` run in the background, stdout and stderr in files."""

    def __init__(self, swarf, program, options, voxel="0.2"):
        self.dir = tempfile.mkdtemp(prefix="swarf-mb-")
        self.out = open(os.path.join(self.dir, "stdout"), "w+")
        self.err = open(os.path.join(self.dir, "stderr"), "w+")
        cmd = [swarf, "simulate", program] + DEMO + ["--voxel", voxel, "--out",
                                                     os.path.join(self.dir, "r.vdb")] + options
        self.proc = subprocess.Popen(cmd, stdout=self.out, stderr=self.err)

    def stderr(self):
        if getattr(self, "err_text", None) is not None:
            return self.err_text
        with open(self.err.name) as f:
            return f.read()

    def wait_for(self, regex, timeout=30.0):
        """The first match of regex in stderr (waits for it)."""
        end = time.time() + timeout
        while time.time() < end:
            m = re.search(regex, self.stderr())
            if m:
                return m
            if self.proc.poll() is not None:
                break
            time.sleep(0.02)
        raise RuntimeError("swarf never printed %r; stderr:\n%s" % (regex, self.stderr()))

    def tcp_port(self):
        return int(self.wait_for(r"Modbus TCP server on [^ ]*:(\d+)").group(1))

    def finish(self, timeout=120.0):
        rc = self.proc.wait(timeout)
        with open(self.out.name) as f:
            out = f.read()
        self.err_text = self.stderr()
        print(out, self.err_text, flush=True)
        atexit.register(shutil.rmtree, self.dir, True)
        return rc, out


def summary_numbers(text):
    """lines, moves and removed mm^3 from swarf's summary."""
    lines = int(re.search(r"lines (\d+), moves", text).group(1))
    moves = int(re.search(r"moves (\d+) \(", text).group(1))
    removed = float(re.search(r"removed ([0-9.]+) mm\^3", text).group(1))
    return lines, moves, removed


def parse_moves(swarf, program):
    """The program's motion moves (rapid, line, arc) listed by `swarf parse`."""
    out = subprocess.run([swarf, "parse", program], capture_output=True, text=True).stdout
    return len(re.findall(r"^\d+ (RAPID|LINE|ARC) ", out, re.M))


def u32(regs, at):
    return regs[at] << 16 | regs[at + 1]


def decode(regs):
    """The documented map (tools/doc/modbus.md), registers 0..19."""
    return {
        "state": regs[0], "permille": regs[1], "line": u32(regs, 2),
        "done": u32(regs, 4), "total": u32(regs, 6), "removed": u32(regs, 8),
        "alarms": regs[10], "error": regs[11], "elapsed": u32(regs, 12),
        "remaining": u32(regs, 14), "tool": regs[16], "heartbeat": regs[17],
        "flags": regs[18], "version": regs[19],
    }


def name_of(regs):
    """Registers 32..63: the program name, two ASCII bytes each, high first."""
    raw = b"".join(struct.pack(">H", r) for r in regs)
    return raw.split(b"\0")[0].decode("ascii")


def raw_request(port, frame, timeout=2.0):
    """Send one raw frame; the bytes answered (b"" if the server closed)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(frame)
        try:
            return s.recv(300)
        except socket.timeout:
            return None


def mbap(tid, unit, pdu):
    return struct.pack(">HHHB", tid, 0, len(pdu) + 1, unit) + pdu


def mbpoll(args, timeout=20):
    """Run mbpoll; {reference: value} of what it printed, and its exit status."""
    p = subprocess.run(["mbpoll"] + args, capture_output=True, text=True, timeout=timeout)
    values = {int(k): int(v) for k, v in re.findall(r"^\[(\d+)\]:\s+(-?\d+)", p.stdout, re.M)}
    return values, p.returncode, p.stdout + p.stderr
