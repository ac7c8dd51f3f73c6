# SPDX-License-Identifier: MPL-2.0
"""modbus_collisions.py SWARF -- collisions reach Modbus: after a run with a
holder that enters the material twice and a cutter that enters a fixture
twice, pymodbus reads register 10 (all alarms: 4 collisions + 1 rapid that
cuts), register 20 (collisions: 4) and the map version (2), in the input and
the holding registers alike.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mbkit  # noqa: E402
from pymodbus.client import ModbusTcpClient  # noqa: E402

swarf = sys.argv[1]
t = mbkit.Failures()
d = tempfile.mkdtemp(prefix="swarf-mbc-")
program = os.path.join(d, "p.ngc")
with open(program, "w") as f:
    f.write("G0 X20 Y20 Z5\nG1 Z-20 F300\nG1 Z-27\nG0 Z30\nG0 X30 Y20 Z2\nG1 X58\nG0 Z30\n"
            "G0 X5 Y5 Z-1\nG0 Z30\nM2\n")
err = open(os.path.join(d, "stderr"), "w+")
proc = subprocess.Popen([swarf, "simulate", program, "--stock", "box:0,0,-40,60,40,0",
                         "--voxel", "0.25", "--tool", "T1=flat,D6,L10,S25", "--holder", "T1=20x40",
                         "--fixture", "box:50,0,0,60,40,5", "--out", os.path.join(d, "r.vdb"),
                         "--quiet", "--modbus", "tcp:127.0.0.1:0", "--modbus-linger", "6"],
                        stderr=err)
port = None
for _ in range(300):
    with open(err.name) as f:
        m = re.search(r"Modbus TCP server on [^ ]*:(\d+)", f.read())
    if m:
        port = int(m.group(1))
        break
    time.sleep(0.02)
t.check("the server starts", port is not None)
client = ModbusTcpClient("127.0.0.1", port=port, timeout=3, retries=1)
t.check("pymodbus connects", client.connect())
regs = None
for _ in range(400):
    rr = client.read_input_registers(0, 21, slave=1)
    if not rr.isError() and rr.registers[0] == 2:
        regs = rr.registers
        break
    time.sleep(0.05)
t.check("the job finishes", regs is not None)
if regs is not None:
    hr = client.read_holding_registers(0, 21, slave=1)
    t.check("holding registers read the same", not hr.isError() and hr.registers[10:21] == regs[10:21])
    t.check("register 10: 5 alarms", regs[10] == 5, str(regs[10]))
    t.check("register 20: 4 collisions", regs[20] == 4, str(regs[20]))
    t.check("map version 2", regs[19] == 2, str(regs[19]))
    t.check("flag bit 3: alarm count > 0", regs[18] & 8 != 0)
client.close()
proc.wait(30)
with open(err.name) as f:
    print(f.read())
shutil.rmtree(d, True)
t.finish()
