#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Regenerates each <case>.expected from LinuxCNC's stand-alone interpreter
# (Debian's linuxcnc-uspace `rs274`), with tools.tbl as the tool table:
#   cd tests/gcode/ccomp && ./make_expected.sh
# The expected files keep rs274's raw output (sequence number, N field, call).
set -e
for f in *.ngc; do
  rs274 -t tools.tbl -g "$f" > "${f%.ngc}.expected" 2>&1 || true
done
