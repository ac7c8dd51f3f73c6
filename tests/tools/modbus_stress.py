# SPDX-License-Identifier: MPL-2.0
"""modbus_stress.py SWARF FIXTURES -- the TCP status server under abuse while
the demo runs: 32 clients poll at once, one sends garbage (and reconnects
each time it is dropped), one connects and never sends nor reads, one floods
requests and never reads the replies, one sends a frame one byte a second.
The job must complete with the right final registers, every poller must be
served to the end, and the abusers must be dropped. Timing is not asserted
here (tools/bench/bench_modbus measures it); run it on an ASan build too.

The Load class is also what tools/bench/bench_modbus uses to load the server.
"""
import os
import socket
import struct
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mbkit  # noqa: E402

READ = mbkit.mbap(1, 1, struct.pack(">BHH", 4, 0, 20))


def recv_exact(s, n):
    data = b""
    while len(data) < n:
        chunk = s.recv(n - len(data))
        if not chunk:
            raise ConnectionError("closed")
        data += chunk
    return data


class Load:
    """The clients above, in threads, against 127.0.0.1:port."""

    def __init__(self, port, pollers=32, period=0.05):
        self.port, self.period = port, period
        self.stop = threading.Event()
        self.replies = [0] * pollers
        self.errors = []
        self.last_regs = [None] * pollers
        self.garbage_drops = 0
        self.flood_dropped = False
        self.slow_dropped = False
        self.threads = [threading.Thread(target=self.poll, args=(i,)) for i in range(pollers)]
        self.threads += [threading.Thread(target=f) for f in (self.garbage, self.flood, self.slow)]
        self.idle = socket.create_connection(("127.0.0.1", port))
        for th in self.threads:
            th.start()

    def connect(self):
        return socket.create_connection(("127.0.0.1", self.port), timeout=10)

    def poll(self, i):
        try:
            with self.connect() as s:
                while not self.stop.is_set():
                    s.sendall(READ)
                    head = recv_exact(s, 9)
                    body = recv_exact(s, head[8])
                    if head[7] != 4 or head[8] != 40:
                        raise ValueError("bad reply %r" % head)
                    self.last_regs[i] = struct.unpack(">20H", body)
                    self.replies[i] += 1
                    time.sleep(self.period)
        except Exception as e:  # noqa: BLE001 -- any failure of a poller is reported
            self.errors.append("poller %d: %r" % (i, e))

    def garbage(self):
        junk = bytes(range(256)) * 2
        while not self.stop.is_set():
            try:
                with self.connect() as s:
                    while not self.stop.is_set():
                        s.sendall(junk)
                        if s.recv(300) == b"":
                            break
            except OSError:
                pass
            self.garbage_drops += 1
            time.sleep(0.05)

    def flood(self):
        try:
            with self.connect() as s:
                s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
                s.settimeout(1.0)
                while not self.stop.is_set():
                    s.sendall(READ * 64)
        except OSError:
            self.flood_dropped = True

    def slow(self):
        try:
            with self.connect() as s:
                for b in READ[:-1]:
                    if self.stop.is_set():
                        return
                    s.sendall(bytes([b]))
                    time.sleep(1.0)
                if s.recv(1) == b"":
                    self.slow_dropped = True
        except OSError:
            self.slow_dropped = True

    def finish(self):
        self.stop.set()
        for th in self.threads:
            th.join(15)
        self.idle.close()


def main():
    mbkit.require()
    swarf, fixtures = sys.argv[1], sys.argv[2]
    t = mbkit.Failures()
    run = mbkit.Swarf(swarf, os.path.join(fixtures, "demo.ngc"),
                      ["--modbus", "tcp:127.0.0.1:0", "--modbus-linger", "8"])
    load = Load(run.tcp_port())
    while True:  # until the job is over, as seen by the pollers
        regs = [r for r in load.last_regs if r]
        if (regs and max(r[0] for r in regs) >= 2) or run.proc.poll() is not None:
            break
        time.sleep(0.1)
    time.sleep(1.0)
    served_at_end = list(load.replies)
    time.sleep(1.0)
    t.check("every poller still served after the job", all(
        b > a for a, b in zip(served_at_end, load.replies)), "%s -> %s" % (served_at_end, load.replies))
    for _ in range(60):  # a frame left half sent is dropped after 5 s
        if load.slow_dropped:
            break
        time.sleep(0.1)
    t.check("client sending a byte a second dropped", load.slow_dropped)
    load.finish()
    t.check("no poller failed", not load.errors, "; ".join(load.errors[:5]))
    t.check("every poller got replies", min(load.replies) >= 5, str(load.replies))
    t.check("garbage client dropped", load.garbage_drops >= 1, str(load.garbage_drops))
    t.check("flooding client that never reads dropped", load.flood_dropped)
    final = mbkit.decode(max(load.last_regs, key=lambda r: r[0]))
    rc, summary = run.finish()
    t.check("swarf exits 0", rc == 0, str(rc))
    lines, moves, removed = mbkit.summary_numbers(summary)
    t.check("final state", final["state"] == 2 and final["permille"] == 1000, str(final))
    t.check("final moves and line", final["done"] == moves and final["line"] == lines, str(final))
    t.check("final removed volume", abs(final["removed"] - removed) <= 0.5)
    print("replies per poller: min %d, max %d; garbage connections dropped: %d" %
          (min(load.replies), max(load.replies), load.garbage_drops))
    t.finish()


if __name__ == "__main__":
    main()
