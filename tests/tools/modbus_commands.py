# SPDX-License-Identifier: MPL-2.0
"""modbus_commands.py SWARF FIXTURES -- with --modbus-commands, a client
pauses, resumes and aborts a running simulation through holding register 64:
while paused no move is done (the heartbeat still beats), after resume moves
go on, abort ends the job with state 3, error 3 and exit status 3 and no
output file. Values that are not commands get exception 03, writes elsewhere
exception 02.
"""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mbkit  # noqa: E402

mbkit.require()
from pymodbus.client import ModbusTcpClient  # noqa: E402

swarf, fixtures = sys.argv[1], sys.argv[2]
t = mbkit.Failures()
run = mbkit.Swarf(swarf, os.path.join(fixtures, "demo.ngc"),
                  ["--modbus", "tcp:127.0.0.1:0", "--modbus-commands", "--modbus-linger", "3"])
c = ModbusTcpClient("127.0.0.1", port=run.tcp_port(), timeout=3, retries=1)
c.connect()


def status():
    return mbkit.decode(c.read_input_registers(0, 20, slave=1).registers)


def wait_until(cond, timeout=60.0):
    """The first status for which cond holds (a long arc can hold a move for seconds)."""
    end = time.time() + timeout
    while True:
        s = status()
        if cond(s) or time.time() > end:
            return s
        time.sleep(0.05)


def exc(rr):
    return getattr(rr, "exception_code", None)


while status()["done"] < 50 and status()["state"] <= 1:
    time.sleep(0.02)
t.check("commands flag set", c.read_discrete_inputs(6, 1, slave=1).bits[0] == 1)
t.check("value 7 is not a command: 03", exc(c.write_register(64, 7, slave=1)) == 3)
t.check("status registers are read-only: 02", exc(c.write_register(1, 1, slave=1)) == 2)
t.check("two registers at 63: 02", exc(c.write_registers(63, [1, 1], slave=1)) == 2)
t.check("pause accepted", not c.write_register(64, 1, slave=1).isError())
a = wait_until(lambda s: s["flags"] & 16)  # the simulation holds at its next move
time.sleep(1.0)
b = status()
t.check("paused flag", a["flags"] & 16 and c.read_discrete_inputs(4, 1, slave=1).bits[0] == 1, str(a))
t.check("no move while paused", a["done"] == b["done"] and b["state"] == 1, "%s %s" % (a, b))
t.check("heartbeat beats while paused", a["heartbeat"] != b["heartbeat"])
t.check("last command reads back", c.read_holding_registers(64, 1, slave=1).registers == [1])
t.check("resume accepted", not c.write_register(64, 2, slave=1).isError())
d = wait_until(lambda s: s["done"] > b["done"] or s["state"] != 1)
t.check("moves go on after resume", d["done"] > b["done"] or d["state"] == 2, "%s %s" % (b, d))
t.check("abort accepted (FC 16)", not c.write_registers(64, [3], slave=1).isError())
e = wait_until(lambda s: s["state"] != 1)
t.check("aborted: state 3, error 3", e["state"] == 3 and e["error"] == 3, str(e))
t.check("aborted before the end", e["done"] < mbkit.parse_moves(swarf, os.path.join(fixtures, "demo.ngc")))
c.close()
out_vdb = os.path.join(run.dir, "r.vdb")
rc, _ = run.finish()
t.check("exit status 3", rc == 3, str(rc))
t.check("says it was aborted", "aborted by a Modbus command" in run.stderr())
t.check("no output written", not os.path.exists(out_vdb))
t.finish()
