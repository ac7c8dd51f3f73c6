#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# vdb_write.sh -- the .vdb writer's leaves compressed on the stock's threads
# (stock/write_leaves.cc) against OpenVDB's own serial loop
# (SWARF_VDB_SERIAL_WRITE=1): the files must be the same byte for byte but
# for the header's random UUID (bytes 22-57). An 80 x 80 x 20 mm box at
# 0.1 mm (over 16384 leaves: more than one round of buffers; 0.18 mm with
# SWARF_TEST_FAST=1, below) cut by a slot, a
# ramp and an arc, on one and on two threads; pyopenvdb then reads the
# parallel file and must find the stock grid with its leaves.
#   vdb_write.sh SWARF
set -u
swarf=$1
if [ "${SWARF_REFERENCE_BUILT:-0}" != 1 ]; then
  echo "SKIPPED: this build has no reference paths; configure with -DSWARF_REFERENCE_PATHS=ON (tools/run test does)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'G21 G90 G17\nG0 X-5 Y10 Z5\nG1 Z-2 F500\nG1 X85\nG1 X40 Y60 Z-6\nG2 X10 Y30 I-10 J-20\nG0 Z5\nM2\n' \
  > "$tmp/p.ngc"
run() { # run NAME THREADS SERIAL
  SWARF_VDB_SERIAL_WRITE=$3 "$swarf" simulate "$tmp/p.ngc" --stock box:0,0,-20,80,80,0 \
    --tool T1=flat,D6,L30 --voxel "$voxel" --threads "$2" --quiet --out "$tmp/$1.vdb" 2> "$tmp/err" ||
    { echo "FAIL: $1: $(cat "$tmp/err")"; exit 1; }
}
# SWARF_TEST_FAST=1 (the sanitized suite: 20 s a run there, most of it
# building the 0.1 mm box): 0.18 mm (18,230 leaves: still two rounds) and the
# two-thread write only; the one-thread one is the same code.
files="par2 par1" voxel=0.1
[ "${SWARF_TEST_FAST:-}" = 1 ] && files=par2 voxel=0.18
run serial 2 1
for f in $files; do run "$f" "${f#par}" 0; done
rc=0
for f in $files; do
  if cmp -s -i 57 "$tmp/serial.vdb" "$tmp/$f.vdb"; then
    echo "ok: $f.vdb = OpenVDB's serial write ($(stat -c %s "$tmp/$f.vdb") bytes) past the UUID"
  else
    echo "FAIL: $f.vdb differs from OpenVDB's serial write: $(cmp -i 57 "$tmp/serial.vdb" "$tmp/$f.vdb" 2>&1)"
    rc=1
  fi
done
/usr/bin/python3 - "$tmp/par2.vdb" <<'PY' || rc=1
import sys
import pyopenvdb as vdb
g = vdb.read(sys.argv[1], "stock")
leaves = g.leafCount()
ok = leaves > 16384 and g.activeVoxelCount() > 0 and g.gridClass == vdb.GridClass.LEVEL_SET
print("%s: pyopenvdb reads the parallel file: %d leaves, %d active voxels"
      % ("ok" if ok else "FAIL", leaves, g.activeVoxelCount()))
sys.exit(0 if ok else 1)
PY
exit $rc
