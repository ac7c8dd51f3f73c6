# SPDX-License-Identifier: MPL-2.0
"""modbus_churn.py SWARF FIXTURES -- the TCP status server's client table under
connection churn (tools/doc/modbus.md: who is closed when the table
is full). 64 polite pollers (32 at 2 Hz, 32 at 1 Hz, raw sockets, one
connection each) fill the 64 slots; then, for ~8 s, ~100 connections a second
come and go (closed at once, left idle, one good request then idle, one
exception-provoking request then idle) beside a garbage sender, a flooder that
never reads, a slow sender and a silent socket, while a newcomer (pymodbus)
asks for the registers every 0.6 s. Last, 40 idle connections are opened at
once (the table is full of pollers and idle sockets younger than a second)
and 5 more newcomers ask.

Asserted: every poll of every poller is answered (100 %: none reset, none
closed, none unanswered within a 10 s hang limit), every newcomer is answered
with the documented map (version register 19 = 2), the abusers are dropped.
The old policy (a newcomer replaces the client idle the longest if idle >= 1 s,
else is turned away) fails it: the 1 Hz pollers are reset by the churn and
the newcomers are turned away. Nothing is timed.
"""
import collections
import os
import shutil
import socket
import struct
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mbkit  # noqa: E402
import modbus_stress  # noqa: E402

mbkit.require()
from pymodbus.client import ModbusTcpClient  # noqa: E402

READ = modbus_stress.READ
BAD_UNIT = mbkit.mbap(2, 9, struct.pack(">BHH", 4, 0, 20))  # exception 0B
BAD_FUNC = mbkit.mbap(3, 1, bytes([0x2B, 0x0E, 0x01, 0x00]))  # exception 01
POLL_LIMIT = 10.0  # a hang limit per poll, not a timing assertion


class Poller:
    """One connection polling input registers 0..19 every `period` seconds;
    a poll that is reset, closed or unanswered counts as failed (and the
    poller reconnects)."""

    def __init__(self, port, period, stop):
        self.port, self.period, self.stop = port, period, stop
        self.ok = self.failed = 0
        self.why = []
        self.last_regs = None
        self.thread = threading.Thread(target=self.run)
        self.thread.start()

    def run(self):
        s = None
        while not self.stop.is_set():
            try:
                if s is None:
                    s = socket.create_connection(("127.0.0.1", self.port), timeout=POLL_LIMIT)
                s.sendall(READ)
                head = modbus_stress.recv_exact(s, 9)
                body = modbus_stress.recv_exact(s, head[8])
                if head[7] != 4 or head[8] != 40:
                    raise ValueError("bad reply %r" % head)
                self.last_regs = struct.unpack(">20H", body)
                self.ok += 1
            except (OSError, ValueError) as e:
                self.failed += 1
                self.why.append(repr(e))
                if s is not None:
                    s.close()
                s = None
            self.stop.wait(self.period)
        if s is not None:
            s.close()


class Churn:
    """~rate connections a second, four kinds in turn; up to `hold` of them
    are kept open (idle), the oldest closed first."""

    def __init__(self, port, rate=100, hold=60):
        self.port, self.rate, self.hold = port, rate, hold
        self.stop = threading.Event()
        self.connects = 0
        self.start = time.time()
        self.held = collections.deque()
        self.thread = threading.Thread(target=self.run)
        self.thread.start()

    def one(self, kind):
        s = socket.create_connection(("127.0.0.1", self.port), timeout=1.0)
        self.connects += 1
        if kind == 0:
            s.close()
            return
        if kind >= 2:
            s.sendall(READ if kind == 2 else (BAD_UNIT if self.connects % 2 else BAD_FUNC))
            try:
                s.recv(300)
            except OSError:
                pass
        self.held.append(s)
        while len(self.held) > self.hold:
            self.held.popleft().close()

    def run(self):
        start, n = time.time(), 0
        while not self.stop.is_set():
            try:
                self.one(n % 4)
            except OSError:
                pass
            n += 1
            pause = start + n / self.rate - time.time()
            if pause > 0:
                time.sleep(pause)

    def finish(self):
        self.stop.set()
        self.thread.join(30)
        self.seconds = time.time() - self.start
        while self.held:
            self.held.popleft().close()


def newcomer(port):
    """A fresh pymodbus client reads registers 0..19 once: the reason it
    failed, or None."""
    client = ModbusTcpClient("127.0.0.1", port=port, timeout=POLL_LIMIT, retries=0)
    try:
        if not client.connect():
            return "cannot connect"
        rr = client.read_input_registers(0, 20, slave=1)
        if rr.isError():
            return str(rr)
        if mbkit.decode(rr.registers)["version"] != 2:
            return "not the documented map: %r" % (rr.registers,)
        return None
    except Exception as e:  # noqa: BLE001 -- pymodbus raises on a reset connection
        return repr(e)
    finally:
        client.close()


def probe(port, count, interval, results):
    for _ in range(count):
        results.append(newcomer(port))
        time.sleep(interval)


def main():
    swarf, fixtures = sys.argv[1], sys.argv[2]
    t = mbkit.Failures()
    run = mbkit.Swarf(swarf, os.path.join(fixtures, "demo.ngc"),
                      ["--modbus", "tcp:127.0.0.1:0", "--modbus-linger", "120"], voxel="0.5")
    port = run.tcp_port()
    stop = threading.Event()
    pollers = []
    for i in range(64):
        pollers.append(Poller(port, 0.5 if i % 2 == 0 else 1.0, stop))
        time.sleep(0.015)  # 64 connections within a second, not in one burst
    for _ in range(200):  # every poller connected and answered once
        if all(p.ok + p.failed for p in pollers):
            break
        time.sleep(0.05)

    churn = Churn(port)
    abusers = modbus_stress.Load(port, pollers=0)
    during = []
    probe(port, 12, 0.6, during)
    time.sleep(0.5)
    churn.finish()
    churn_rate = churn.connects / churn.seconds

    idle = []
    for i in range(40):  # younger than a second, half of them asked once
        try:
            s = socket.create_connection(("127.0.0.1", port), timeout=2.0)
            idle.append(s)
            if i % 2:
                s.sendall(READ)
                s.recv(300)
        except OSError:
            pass
    full = []
    probe(port, 5, 0.1, full)
    for _ in range(60):  # the slow sender is dropped 5 s after its first byte
        if abusers.slow_dropped:
            break
        time.sleep(0.1)
    abusers.finish()
    for s in idle:
        s.close()
    time.sleep(1.0)  # one more round of polls after the abuse
    stop.set()
    for p in pollers:
        p.thread.join(POLL_LIMIT + 5)

    polls = sum(p.ok + p.failed for p in pollers)
    failed = sum(p.failed for p in pollers)
    failed_slow = sum(p.failed for p in pollers if p.period == 1.0)
    why = [w for p in pollers for w in p.why]
    print("churn: %d connections (~%.0f/s); pollers: %d polls, %d failed (%.1f %% answered; "
          "1 Hz pollers %d failed, 2 Hz pollers %d failed)" %
          (churn.connects, churn_rate, polls, failed, 100.0 * (polls - failed) / max(polls, 1),
           failed_slow, failed - failed_slow))
    print("newcomers during churn: %d/%d answered; with the table full of idle sockets: %d/%d" %
          (during.count(None), len(during), full.count(None), len(full)))
    t.check("churn reached ~100 connections a second", churn.connects >= 400, str(churn.connects))
    t.check("every poller polled", min(p.ok for p in pollers) >= 4, str([p.ok for p in pollers]))
    t.check("every poll answered (none reset, closed or unanswered)", failed == 0,
            "%d of %d failed: %s" % (failed, polls, "; ".join(sorted(set(why))[:5])))
    t.check("every newcomer answered during churn", during.count(None) == len(during),
            str([w for w in during if w]))
    t.check("every newcomer answered with the table full of idle sockets",
            full.count(None) == len(full), str([w for w in full if w]))
    t.check("garbage client dropped", abusers.garbage_drops >= 1, str(abusers.garbage_drops))
    t.check("flooding client that never reads dropped", abusers.flood_dropped)
    t.check("client sending a byte a second dropped", abusers.slow_dropped)
    regs = [p.last_regs for p in pollers if p.last_regs]
    t.check("the job finished while served", regs and max(r[0] for r in regs) == 2)
    run.proc.terminate()  # it would linger 120 s more
    run.proc.wait(30)
    shutil.rmtree(run.dir, True)
    t.finish()


if __name__ == "__main__":
    main()
