#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# round2.sh SWARF [CASE...] -- the hardening reproducers (round
# 2), one function a case, each made of its own inputs in a scratch folder.
# Prints one line a case, FIXED or PRESENT, and a count. With CASEs it runs
# those and fails when any is PRESENT (ctest runs the fixed ones so, leaving
# out c_api_null and modbus_spin, which run as tools_sim_api and
# tools_modbus_spin); with none it runs all and only reports.
set -u
swarf=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
S=(--stock box:0,0,-5,20,20,0 --tool T1=flat,D4 --voxel 0.5 --quiet)
printf 'G21 G90\nG0 Z5\nG0 X5 Y5\nG1 Z-2 F300\nG1 X15\nG0 Z5\nM2\n' > p.ngc
if ! "$swarf" simulate p.ngc "${S[@]}" --out a.vdb ||
  ! "$swarf" simulate p.ngc "${S[@]}" --out b.vdb --mesh b.stl; then
  echo "FAIL: the inputs could not be made"
  exit 1
fi

sum() { sha256sum "$1" 2> /dev/null | cut -c1-64; }

# Each case: 0 (FIXED) when swarf refuses or behaves, 1 (PRESENT) otherwise.
case_compare_image_input() { # swarf compare A.vdb B.vdb --image A.vdb overwrote A
  local before; before=$(sum a.vdb)
  "$swarf" compare a.vdb b.vdb --image a.vdb > /dev/null 2> err
  [ $? -eq 2 ] && [ "$(sum a.vdb)" = "$before" ] && grep -q "is the input A" err
}
case_compare_mesh_input() { # --mesh the design STL overwrote it
  local before; before=$(sum b.stl)
  "$swarf" compare a.vdb b.stl --mesh b.stl > /dev/null 2> err
  [ $? -eq 2 ] && [ "$(sum b.stl)" = "$before" ] && grep -q "is the input B" err
}
case_mesh_over_fixture() { # simulate --mesh onto the --fixture STL
  local before; before=$(sum b.stl)
  "$swarf" simulate p.ngc "${S[@]}" --fixture stl:b.stl --out c.vdb --mesh b.stl 2> err
  [ $? -eq 2 ] && [ "$(sum b.stl)" = "$before" ] && [ ! -e c.vdb ] && grep -q "fixture" err
}
case_out_over_subroutine() { # --out onto a subroutine file the program calls
  mkdir -p subs
  printf 'o<foo> sub\nG0 X2\no<foo> endsub\nM2\n' > subs/foo.ngc
  printf 'G21 G0 Z5\no<foo> call\nM2\n' > call.ngc
  local before; before=$(sum subs/foo.ngc)
  "$swarf" simulate call.ngc "${S[@]}" --subroutine-path subs --out subs/foo.ngc 2> err
  [ $? -eq 2 ] && [ "$(sum subs/foo.ngc)" = "$before" ] && grep -q "subroutine" err
}
case_sweep_user_file() { # the stale-temporary sweep removed a user's OUT.tmp.N
  sh -c 'exit 0' &
  local dead=$!
  wait $dead
  echo mine > "d.vdb.tmp.$dead"
  "$swarf" simulate p.ngc "${S[@]}" --out d.vdb 2> /dev/null && [ -e d.vdb ] &&
    [ "$(cat "d.vdb.tmp.$dead" 2> /dev/null)" = mine ]
}
case_long_output_name() { # a long --mesh name: --out written, the mesh not (all-or-none broken)
  local long
  long=$(printf 'm%.0s' $(seq 248)).stl
  "$swarf" simulate p.ngc "${S[@]}" --out e.vdb --mesh "$long" 2> err
  [ $? -eq 2 ] && [ ! -e e.vdb ] && [ ! -e "$long" ] && grep -q "too long" err
}

case_vdb_nan() { # a .vdb with a NaN value was accepted as stock and as design
  /usr/bin/python3 -c "
import pyopenvdb as vdb, sys
g = vdb.read(sys.argv[1], 'stock')
g.getAccessor().setValueOn((10, 10, -2), float('nan'))
vdb.write(sys.argv[2], [g])" a.vdb nan.vdb 2> /dev/null || return 1
  "$swarf" simulate p.ngc "${S[@]/box:0,0,-5,20,20,0/vdb:nan.vdb}" --out f.vdb 2> err
  [ $? -eq 2 ] && [ ! -e f.vdb ] && grep -q "nan.vdb: a value that is not a number" err || return 1
  "$swarf" simulate p.ngc "${S[@]}" --design nan.vdb --out f.vdb 2> err
  [ $? -eq 2 ] && [ ! -e f.vdb ] && grep -q "nan.vdb: a value that is not a number" err
}
case_table_z_huge() { # a tool table's Z1e300 gave an infinite time
  printf 'T1 P1 D4 Z1e300\n' > z.tbl
  "$swarf" simulate p.ngc --stock box:0,0,-5,20,20,0 --tool-table z.tbl --voxel 0.5 --out g.vdb --quiet \
    2> err
  [ $? -eq 2 ] && [ ! -e g.vdb ] && grep -q "z.tbl:1: .*beyond 10 m" err
}
case_grbl_m56() { # --dialect grbl refused M56, which grbl has (parking override)
  printf 'G21\nM56\nG0 X1\nM2\n' > m56.nc
  "$swarf" parse --dialect grbl m56.nc > /dev/null 2> err && grep -q "M56: parking" err
}
case_out_fifo() { # --out a FIFO: "Illegal seek" after the run (or a hang with no reader)
  mkfifo fifo.vdb
  timeout 20 "$swarf" simulate p.ngc "${S[@]}" --out fifo.vdb 2> err
  local rc=$?
  rm -f fifo.vdb
  [ $rc -eq 2 ] && grep -q "it is a FIFO" err
}
case_latin1_report() { # a Latin-1 file name with --report said "out of memory"
  local name
  name=$(printf 'caf\351.ngc')
  cp p.ngc "$name"
  "$swarf" simulate "$name" "${S[@]}" --out h.vdb --report h.json 2> err &&
    /usr/bin/python3 -c "import json,sys; sys.exit(not json.load(open('h.json'))['inputs']['program'].endswith('caf\u00e9.ngc'))"
}
case_peck_tiny_q() { # G83 with Q0.000001 ran 7 s into "out of memory"
  printf 'G21 G90 G0 Z5\nG83 X0 Y0 Z-10 R1 Q0.000001 F100\nM2\n' > q.ngc
  timeout 20 "$swarf" parse --quiet q.ngc 2> err
  [ $? -eq 2 ] && grep -q "q.ngc:2:19: G83 makes 11000000 pecks" err
}
case_peck_huge_l() { # G73 with a large L: pecks times repeats, not lines, is the work
  printf 'G21 G91 G0 Z5\nG73 X0.1 Z-2 R1 Q0.1 L100000 F100\nM2\n' > l.ngc
  timeout 20 "$swarf" parse --quiet l.ngc 2> err
  [ $? -eq 2 ] && grep -q "G73 makes 2000000 pecks" err
}
case_threads_as_limit() { # --threads 300 under an address-space limit aborted (TBB)
  # ASan's shadow memory cannot live under ulimit -v: not checkable in the sanitized build
  grep -qa __asan_init "$swarf" && { echo "  (threads_as_limit: sanitized build, not run)"; return 0; }
  (ulimit -v 1000000 && "$swarf" simulate p.ngc "${S[@]}" --threads 300 --out t.vdb 2> err)
  [ $? -eq 2 ] && [ ! -e t.vdb ] && grep -q "address-space limit" err
}
case_sub_fifo() { # a FIFO at a subroutine path blocked the call for ever
  mkdir -p fifos && rm -f fifos/foo.ngc && mkfifo fifos/foo.ngc
  printf 'G21 G0 Z5\no<foo> call\nM2\n' > callf.ngc
  timeout 20 "$swarf" parse --subroutine-path fifos callf.ngc > /dev/null 2> err
  [ $? -eq 2 ] && grep -q "callf.ngc:2:1: o<foo> call: fifos/foo.ngc: a FIFO" err
}
case_sub_dev_zero() { # /dev/zero at a subroutine path was read for ever
  mkdir -p zeros && ln -sf /dev/zero zeros/bar.ngc
  printf 'G21 G0 Z5\no<bar> call\nM2\n' > callz.ngc
  timeout 20 "$swarf" parse --subroutine-path zeros callz.ngc > /dev/null 2> err
  [ $? -eq 2 ] && grep -q "o<bar> call: zeros/bar.ngc: not a regular file" err
}
case_tiny_tool_values() { # tiny tool values exited 1 with no location (now: cutter size bounds)
  printf 'T1 P1 D1e-300 Z0\n' > tiny.tbl
  "$swarf" simulate p.ngc --stock box:0,0,-5,20,20,0 --tool T1=flat,D1e-300 --voxel 0.5 \
    --out u.vdb --quiet 2> err
  [ $? -eq 2 ] && grep -q -- "--tool: D: the diameter 1e-300 mm is below 0.001 mm" err || return 1
  "$swarf" simulate p.ngc --stock box:0,0,-5,20,20,0 --tool-table tiny.tbl --voxel 0.5 \
    --out u.vdb --quiet 2> err
  [ $? -eq 2 ] && [ ! -e u.vdb ] && grep -q "tiny.tbl:1: the diameter must be between" err
}
case_loop_helix_turns() { # a loop of many-turn helixes: the bound counted lines, not turns
  printf 'G21 G90 G17\nG0 X10 Y10 Z5\n#1=0\no1 while [#1 lt 100000]\nG2 X10 Y10 I5 Z-1 P1000 F1000\n#1=[#1+1]\no1 endwhile\nM2\n' > hx.ngc
  timeout 60 "$swarf" simulate hx.ngc "${S[@]}" --out hx.vdb 2> err
  [ $? -eq 2 ] && [ ! -e hx.vdb ] && grep -q "hx.ngc:5:1: Work limit reached (5000000: lines run by loops" err
}
case_loop_pecks() { # a loop of pecking cycles: each within its own bound, the loop without one
  printf 'G21 G90\nG0 X10 Y10 Z5\n#1=0\no1 while [#1 lt 100000]\nG83 X10 Y10 Z-4 R1 Q0.001 F100\n#1=[#1+1]\no1 endwhile\nM2\n' > pk.ngc
  timeout 60 "$swarf" parse --quiet pk.ngc 2> err # 5000 pecks a cycle: 1,000 cycles at most
  [ $? -eq 2 ] && grep -q "pk.ngc:5:1: Work limit reached (5000000: " err || return 1
  timeout 60 "$swarf" simulate pk.ngc "${S[@]}" --work-limit 200000 --out pk.vdb 2> err
  [ $? -eq 2 ] && [ ! -e pk.vdb ] && grep -q "pk.ngc:5:1: Work limit reached (200000: " err
}
case_vdb_stock_named() { # a bad .vdb stock was blamed on a program line (and named twice)
  echo garbage > bad.vdb
  "$swarf" simulate p.ngc --stock vdb:bad.vdb --tool T1=flat,D4 --out v.vdb 2> err
  [ $? -eq 2 ] && [ ! -e v.vdb ] && grep -q "^swarf simulate: --stock: bad.vdb: not a readable VDB file" err &&
    ! grep -q "p.ngc:" err
}
sanitized() { # ASan's shadow memory cannot live under ulimit -v, nor MPI's exit leak-free
  grep -qa __asan_init "$swarf" && { echo "  ($1: sanitized build, not run)"; return 0; }
  return 1
}
case_stl_stock_tiny_voxel() { # an STL stock at a tiny voxel: refused up front, not out of memory
  sanitized stl_stock_tiny_voxel && return 0
  (ulimit -v 4000000 && timeout 60 "$swarf" simulate p.ngc --stock stl:b.stl --tool T1=flat,D4 \
    --voxel 0.001 --out s.vdb 2> err)
  [ $? -eq 2 ] && [ ! -e s.vdb ] && grep -q "b.stl: the mesh's surface is too large for this voxel" err
}
case_design_band() { # the design's band (4 tolerances) in the size check
  sanitized design_band && return 0
  (ulimit -v 4000000 && timeout 60 "$swarf" simulate p.ngc "${S[@]/0.5/0.05}" --design b.stl \
    --tolerance 5 --out band.vdb 2> err)
  local rc=$?; [ $rc -eq 2 ] && [ ! -e band.vdb ] && grep -q -- "--design: b.stl: " err || { echo "  design_band: exit $rc: $(head -c 300 err)"; return 1; }
}
py() { # the Python module of this build, under Debian's Python (numpy, pyopenvdb)
  PYTHONPATH="$(dirname "$swarf")/../python" /usr/bin/python3 -c "$1"
}
have_py() { # a sanitized libswarf cannot load into a plain Python (tools/doc/testing.md)
  grep -qa __asan_init "$swarf" && { echo "  (sanitized build: the Python cases not run)" >&2; return 1; }
  [ -f "$(dirname "$swarf")/../python/swarf/__init__.py" ] && [ -x /usr/bin/python3 ] && return 0
  echo "  (the Python module is not built beside $swarf: not run)" >&2
  return 1
}
case_py_library_size() { # the library had no size check: Python ran out of memory after seconds
  have_py || return 0
  (ulimit -v 3000000 && timeout 60 env PYTHONPATH="$(dirname "$swarf")/../python" /usr/bin/python3 -c "
import swarf, sys
try:
    swarf.simulate(text='G0 X1\nM2\n', stock='box:0,0,-100,100,100,0', tools='T1=flat,D4', voxel=0.03)
except swarf.SwarfError as e:
    sys.exit(0 if 'give a voxel of' in str(e) else 1)
sys.exit(1)")
}
case_py_close_in_callback() { # close() inside a progress callback segfaulted
  have_py || return 0
  py "
import swarf
sim = swarf.Simulation('box:0,0,-5,20,10,0', ['T1=flat,D4'], voxel=0.25, progress=lambda p: sim.close())
try:
    sim.feed('G0 X5 Y5 Z2\nG1 Z-1 F100\nG1 X15\nM2\n')
except swarf.SwarfError:
    pass"
}
case_py_stock_int() { # swarf.Stock(12345678) segfaulted
  have_py || return 0
  py "
import swarf, sys
try:
    swarf.Stock(12345678)
except TypeError:
    sys.exit(0)
sys.exit(1)"
}
case_py_batch_band() { # Python accepted batch=0 and -1, and turned band=2**32+3 into 3
  have_py || return 0
  py "
import swarf, sys
bad = 0
for kw in (dict(batch=0), dict(batch=-1), dict(band=2**32 + 3)):
    try:
        swarf.simulate(text='M2\n', stock='box:0,0,-5,20,10,0', tools='T1=flat,D4', **kw)
        bad += 1
    except (ValueError, TypeError, OverflowError):
        pass
sys.exit(bad)"
}
case_mpi_different_inputs() { # ranks given different programs: rank 0 spun in a collective
  sanitized mpi_different_inputs && return 0 # tools_mpi runs MPI there
  command -v mpirun > /dev/null || { echo "  (mpi_different_inputs: no mpirun, not run)"; return 0; }
  mkdir -p wa wb
  printf 'G21 G90 G0 Z5\nG0 X5 Y5\nG1 Z-2 F300\nG1 X15\nG0 Z5\nM2\n' > wa/p.ngc
  printf 'G21 G90 G0 Z5\nG0 X5 Y5\nG1 Z-2 F300\nG1 X15 Y15\nG0 Z5\nM2\n' > wb/p.ngc
  local job=("$swarf" simulate p.ngc "${S[@]}" --out "$work/mixed.vdb")
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 120 mpirun --oversubscribe \
    -n 1 --wdir "$work/wa" "${job[@]}" : -n 1 --wdir "$work/wb" "${job[@]}" > /dev/null 2> err
  local rc=$?
  [ $rc -ne 0 ] && [ $rc -ne 124 ] && [ ! -e mixed.vdb ] && grep -q "rank 1 of 2 was given a different program" err
}
case_c_api_null() { # swarf_sim_parse_stock(spec, NULL, &err) segfaulted (the C API's checks)
  local t; t="$(dirname "$swarf")/../tests/tools/test_sim_api"
  [ -x "$t" ] || { echo "  (c_api_null: $t not built, not run)"; return 0; }
  "$t" > /dev/null 2>&1 # tools_sim_api: NULL outputs and ranges refused with the argument's name
}
case_modbus_spin() { # TCP spun out of descriptors, RTU after its line was lost (tools_modbus_spin)
  local t="$here/../tools/modbus_spin.py"
  command -v socat > /dev/null || { echo "  (modbus_spin: no socat, not run)"; return 0; }
  timeout 300 /usr/bin/python3 "$t" "$swarf" > /dev/null 2>&1
}

all=(compare_image_input compare_mesh_input mesh_over_fixture out_over_subroutine
  sweep_user_file long_output_name vdb_nan table_z_huge grbl_m56 out_fifo latin1_report
  peck_tiny_q peck_huge_l threads_as_limit sub_fifo sub_dev_zero tiny_tool_values
  loop_helix_turns loop_pecks vdb_stock_named stl_stock_tiny_voxel design_band py_library_size
  py_close_in_callback py_stock_int py_batch_band mpi_different_inputs c_api_null modbus_spin)
[ $# -gt 0 ] && all=("$@")
fixed=0 present=0
for c in "${all[@]}"; do
  if "case_$c"; then echo "FIXED   $c"; fixed=$((fixed + 1)); else echo "PRESENT $c"; present=$((present + 1)); fi
done
echo "$fixed fixed, $present present"
[ $# -eq 0 ] || [ $present -eq 0 ]
