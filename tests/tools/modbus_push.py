# SPDX-License-Identifier: MPL-2.0
"""modbus_push.py SWARF FIXTURES -- push mode into a pymodbus server playing
the controller: swarf writes the status block into holding registers
100..163 of unit 5 every 0.2 s while the demo runs (state 1 seen, progress
never going back) and the final state at the end (1000 per-mille, the
lines, moves and removed volume of the summary, the program name). A second
push target where nobody listens is reported once and slows nothing down.
"""
import asyncio
import os
import socket
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mbkit  # noqa: E402

mbkit.require()
from pymodbus.datastore import (ModbusSequentialDataBlock, ModbusServerContext,  # noqa: E402
                                ModbusSlaveContext)
from pymodbus.server.async_io import ModbusTcpServer  # noqa: E402

swarf, fixtures = sys.argv[1], sys.argv[2]
t = mbkit.Failures()
ADDRESS, UNIT = 100, 5

store = ModbusSlaveContext(hr=ModbusSequentialDataBlock(0, [0] * 300), zero_mode=True)
context = ModbusServerContext(slaves={UNIT: store}, single=False)
ready = threading.Event()
box = {}


def serve():
    async def main():
        server = ModbusTcpServer(context, address=("127.0.0.1", 0))
        task = asyncio.ensure_future(server.serve_forever())
        await server.serving
        box["port"] = server.server.sockets[0].getsockname()[1]
        ready.set()
        await task
    asyncio.run(main())


threading.Thread(target=serve, daemon=True).start()
ready.wait(10)
port = box["port"]
with socket.socket() as s:  # a free port that nobody listens on
    s.bind(("127.0.0.1", 0))
    dead = s.getsockname()[1]

run = mbkit.Swarf(swarf, os.path.join(fixtures, "demo.ngc"), [
    "--modbus-push", "tcp:127.0.0.1:%d,unit=%d,address=%d,interval=0.2" % (port, UNIT, ADDRESS),
    "--modbus-push", "tcp:127.0.0.1:%d,unit=1,address=0,interval=0.2" % dead])
samples = []
while run.proc.poll() is None:
    samples.append(mbkit.decode(store.getValues(3, ADDRESS, 20)))
    time.sleep(0.05)
rc, summary = run.finish()
regs = store.getValues(3, ADDRESS, 64)
final = mbkit.decode(regs)
t.check("swarf exits 0", rc == 0, str(rc))
running = [s for s in samples if s["state"] == 1]
t.check("running state pushed", len(running) >= 2, "%d" % len(running))
t.check("progress never goes back", all(a["permille"] <= b["permille"] for a, b in zip(samples, samples[1:])))
lines, moves, removed = mbkit.summary_numbers(summary)
t.check("final state 2, 1000", final["state"] == 2 and final["permille"] == 1000, str(final))
t.check("final moves = summary", final["done"] == moves == final["total"], "%s vs %d" % (final, moves))
t.check("final line = lines", final["line"] == lines)
t.check("removed = summary", abs(final["removed"] - removed) <= 0.5, "%d vs %.1f" % (final["removed"], removed))
t.check("program name", mbkit.name_of(regs[32:64]) == "demo.ngc")
t.check("nothing written outside the block", store.getValues(3, ADDRESS - 1, 1) == [0] and
        store.getValues(3, ADDRESS + 64, 1) == [0])
err = run.stderr()
t.check("dead target reported once", err.count("Modbus push to 127.0.0.1:%d failed" % dead) == 1, err)
t.finish()
