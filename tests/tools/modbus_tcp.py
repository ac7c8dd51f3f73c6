# SPDX-License-Identifier: MPL-2.0
"""modbus_tcp.py SWARF FIXTURES -- real clients follow a running simulation
over Modbus TCP: pymodbus and mbpoll poll the documented map while the demo
runs; progress and moves only grow; the final state shows 1000 per-mille, the
line, move count and removed volume of swarf's own summary and the move count
of `swarf parse`; the standard exceptions come back for unmapped addresses,
writes, a wrong unit and malformed PDUs; garbage does not hurt the server.
"""
import os
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mbkit  # noqa: E402

mbkit.require("mbpoll")
from pymodbus.client import ModbusTcpClient  # noqa: E402

swarf, fixtures = sys.argv[1], sys.argv[2]
program = os.path.join(fixtures, "demo.ngc")
t = mbkit.Failures()
UNIT = 7

run = mbkit.Swarf(swarf, program, ["--modbus", "tcp:127.0.0.1:0,unit=%d" % UNIT,
                                   "--modbus-linger", "5"])
port = run.tcp_port()
client = ModbusTcpClient("127.0.0.1", port=port, timeout=3, retries=1)
t.check("pymodbus connects", client.connect())

# mbpoll, in parallel with pymodbus, while the job runs: 32-bit moves done
# (mbpoll's own decoding, high word first) and the state.
mbpoll_seen = []
job_over = threading.Event()


def mbpoll_loop():
    while not job_over.is_set():
        v, rc, _ = mbkit.mbpoll(["-m", "tcp", "-p", str(port), "-a", str(UNIT), "-t", "3:int",
                                 "-B", "-0", "-r", "4", "-c", "1", "-1", "127.0.0.1"])
        if rc == 0 and 4 in v:
            mbpoll_seen.append(v[4])
        time.sleep(0.1)


poller = threading.Thread(target=mbpoll_loop)
poller.start()

samples = []
while True:
    rr = client.read_input_registers(0, 20, slave=UNIT)
    if rr.isError():
        t.check("input registers readable while running", False, str(rr))
        break
    s = mbkit.decode(rr.registers)
    samples.append(s)
    if s["state"] != 1 or run.proc.poll() is not None:
        break
    time.sleep(0.05)
job_over.set()
poller.join()

running = [s for s in samples if s["state"] == 1]
t.check("state 1 (running) seen", len(running) >= 5, "%d samples" % len(running))
t.check("state 2 after running", samples[-1]["state"] == 2, str(samples[-1]))
t.check("progress monotonic", all(a["permille"] <= b["permille"] for a, b in zip(samples, samples[1:])))
t.check("moves done monotonic", all(a["done"] <= b["done"] for a, b in zip(samples, samples[1:])))
t.check("progress below 1000 while running", all(s["permille"] < 1000 for s in running))
t.check("progress grows while running", len(running) > 1 and running[-1]["permille"] > running[0]["permille"])
t.check("heartbeat moves", len({s["heartbeat"] for s in running}) > 1)
t.check("map version 2", all(s["version"] == 2 for s in samples))
t.check("mbpoll read moves while running", len(mbpoll_seen) >= 2, str(mbpoll_seen))
t.check("mbpoll values monotonic", mbpoll_seen == sorted(mbpoll_seen), str(mbpoll_seen))

expected_total = mbkit.parse_moves(swarf, program)
totals = {s["total"] for s in running if s["total"]}
t.check("moves in the program = swarf parse", totals == {expected_total}, "%s vs %d" % (totals, expected_total))
t.check("remaining seconds estimated while running",
        any(s["remaining"] != 0xFFFFFFFF for s in running if s["done"] > 0))

# Final state, read as holding registers (FC 03) and by mbpoll, during the linger.
hr = client.read_holding_registers(0, 64, slave=UNIT)
final = mbkit.decode(hr.registers)
t.check("final state 2", final["state"] == 2 and final["error"] == 0, str(final))
t.check("final progress 1000", final["permille"] == 1000)
t.check("final remaining 0", final["remaining"] == 0)
t.check("final tool T2", final["tool"] == 2, str(final["tool"]))
t.check("program name", mbkit.name_of(hr.registers[32:64]) == "demo.ngc", mbkit.name_of(hr.registers[32:64]))
di = client.read_discrete_inputs(0, 7, slave=UNIT)
t.check("discrete inputs: finished, total known", di.bits[:7] == [0, 1, 0, 0, 0, 1, 0], str(di.bits))
v, rc, out = mbkit.mbpoll(["-m", "tcp", "-p", str(port), "-a", str(UNIT), "-t", "4", "-0", "-r", "0",
                           "-c", "2", "-1", "127.0.0.1"])
t.check("mbpoll reads the final state", rc == 0 and v.get(0) == 2 and v.get(1) == 1000, out)

# Exceptions (codes from the Modbus application protocol).
def exc(rr):
    return getattr(rr, "exception_code", None)


t.check("input register 64 unmapped: 02", exc(client.read_input_registers(64, 1, slave=UNIT)) == 2)
t.check("input registers 60..65 unmapped: 02", exc(client.read_input_registers(60, 6, slave=UNIT)) == 2)
t.check("holding register 65 unmapped: 02", exc(client.read_holding_registers(65, 1, slave=UNIT)) == 2)
t.check("discrete input 7 unmapped: 02", exc(client.read_discrete_inputs(7, 1, slave=UNIT)) == 2)
t.check("no coils: 02", exc(client.read_coils(0, 1, slave=UNIT)) == 2)
t.check("write refused: 01", exc(client.write_register(64, 1, slave=UNIT)) == 1)
t.check("write of status refused: 01", exc(client.write_registers(0, [5, 5], slave=UNIT)) == 1)
t.check("wrong unit: 0B", exc(client.read_input_registers(0, 1, slave=UNIT + 1)) == 0x0B)
t.check("unit 255 accepted", not client.read_input_registers(0, 1, slave=255).isError())

# Raw frames: a PDU shorter than its function needs gets 03; unknown
# function 01; a frame that is not Modbus TCP closes that connection only.
r = mbkit.raw_request(port, mbkit.mbap(9, UNIT, bytes([0x04, 0x00, 0x00])))
t.check("short PDU: exception 03", r is not None and r[7:9] == bytes([0x84, 0x03]), repr(r))
r = mbkit.raw_request(port, mbkit.mbap(10, UNIT, bytes([0x2B, 0x0E, 0x01, 0x00])))
t.check("unknown function: exception 01", r is not None and r[7:9] == bytes([0xAB, 0x01]), repr(r))
r = mbkit.raw_request(port, b"GET / HTTP/1.0\r\n\r\n")
t.check("garbage: connection closed", r == b"", repr(r))
r = mbkit.raw_request(port, mbkit.mbap(11, UNIT, bytes([0x04, 0x00, 0x00, 0x00, 0x01])))
t.check("still serving after garbage", r is not None and r[7:9] == bytes([0x04, 0x02]), repr(r))
client.close()

rc, summary = run.finish()
t.check("swarf exits 0", rc == 0, str(rc))
lines, moves, removed = mbkit.summary_numbers(summary)
t.check("final line = lines read", final["line"] == lines, "%d vs %d" % (final["line"], lines))
t.check("final moves = report", final["done"] == moves and final["total"] == moves,
        "%d/%d vs %d" % (final["done"], final["total"], moves))
t.check("moves = swarf parse", moves == expected_total)
t.check("removed volume = report", abs(final["removed"] - removed) <= 0.5, "%d vs %.1f" % (final["removed"], removed))
t.check("elapsed seconds", 0 <= final["elapsed"] <= 600, str(final["elapsed"]))
t.finish()
