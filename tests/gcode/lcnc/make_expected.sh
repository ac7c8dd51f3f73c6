#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Regenerates each <case>.expected from LinuxCNC's stand-alone interpreter
# (Debian's linuxcnc-uspace `rs274`), with tools.tbl as the tool table and
# lcnc.ini (the subroutine path) as its INI; cases named *-bdel* run with
# the block delete switch on (-b):
#   cd tests/gcode/lcnc && ./make_expected.sh
# The expected files keep rs274's raw output (sequence number, N field, call).
set -e
for f in *.ngc; do
  b=""
  case "$f" in *-bdel*) b="-b" ;; esac
  rs274 $b -i lcnc.ini -t tools.tbl -g "$f" > "${f%.ngc}.expected" 2>&1 || true
done
