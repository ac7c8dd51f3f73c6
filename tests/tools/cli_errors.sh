#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# cli_errors.sh SWARF -- bad input to `swarf simulate`: each case must exit 2,
# say where the problem is (FILE:LINE:COL or the flag), and leave no output.
set -u
swarf=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0

# expect NAME REGEX PROGRAM-TEXT [extra options...]
expect() {
  local name=$1 regex=$2 text=$3
  shift 3
  printf '%b' "$text" > "$dir/prog.ngc"
  rm -f "$dir"/out.* "$dir"/*.tmp*
  "$swarf" simulate "$dir/prog.ngc" --out "$dir/out.vdb" --mesh "$dir/out.stl" --quiet "$@" \
    > "$dir/stdout" 2> "$dir/stderr"
  local rc=$? leftovers
  leftovers=$(ls "$dir" | grep -v -E '^(prog.ngc|stdout|stderr)$')
  if [ $rc -eq 2 ] && grep -qE -- "$regex" "$dir/stderr" && [ -z "$leftovers" ]; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1))
    echo "FAIL $name: exit $rc, leftovers [$leftovers], stderr:"; cat "$dir/stderr"
  fi
}

stock=(--stock box:0,0,-10,40,30,0)
tool=(--tool T1=ball,D3,L12)
expect unknown-word 'prog\.ngc:2:1: .*Q' 'G0 X1\nQ5\n' "${stock[@]}" "${tool[@]}"
expect unknown-gcode 'prog\.ngc:1:1: .*G12' 'G12.5 X1\n' "${stock[@]}" "${tool[@]}"
expect malformed-number 'prog\.ngc:3:(4|5|6|7|8|9):' 'G0 Z5\nG0 X1\nG1 X1.2.3 F100\n' "${stock[@]}" "${tool[@]}"
expect bad-arc-radius 'prog\.ngc:2:[0-9]+: .*[Rr]adius' 'G0 X0 Y0 Z1\nG2 X10 Y0 I4 J0 F100\n' "${stock[@]}" "${tool[@]}"
expect arc-r-too-small 'prog\.ngc:2:[0-9]+: ' 'G0 X0 Y0 Z1\nG2 X10 Y0 R2 F100\n' "${stock[@]}" "${tool[@]}"
expect missing-tool 'prog\.ngc:3:1: Requested tool 3 not found in the tool table' 'G0 Z5\nG0 X1\nT3 M6\nG0 X2\n' \
  "${stock[@]}" --tool T1=ball,D3 --tool T2=flat,D6
expect stock-min-max '--stock: X min 10 is not below X max 0' 'G0 X1\n' --stock box:10,0,-10,0,30,0 "${tool[@]}"
expect stock-garbage '--stock: ' 'G0 X1\n' --stock box:1,2,3 "${tool[@]}"
expect tool-garbage '--tool: ' 'G0 X1\n' "${stock[@]}" --tool T1=sphere,D3
expect bull-without-r '--tool: ' 'G0 X1\n' "${stock[@]}" --tool T1=bull,D6
expect vee-without-angle '--tool: A: the included angle is required' 'G0 X1\n' "${stock[@]}" --tool T1=vee,D6
expect vee-bad-field '--tool: unknown field "X3" for vee \(use DAL\)' 'G0 X1\n' "${stock[@]}" --tool T1=vee,D6,A90,X3
expect apt-inconsistent '--tool: F: .* F = \(R \+ E sin A\) / cos A = 1 \(got 3\)' 'G0 X1\n' "${stock[@]}" \
  --tool T1=apt,D6,R1,E2,F3,A0,B0,H10
expect qss-axis '--tool: the QSS profile crosses its axis' 'G0 X1\n' "${stock[@]}" --tool T1=qss,-1,1,0,0
expect lollipop-neck '--tool: K: the neck must be thinner' 'G0 X1\n' "${stock[@]}" --tool T1=lollipop,D6,K6
# an axis swarf's machines do not have: named, with what to do
expect u-axis 'prog\.ngc:1:7: U5: the U axis is not supported .*remove the U words' 'G0 X1 U5\n' \
  "${stock[@]}" "${tool[@]}"
# one task of a multi-task launch that MPI sees alone (srun without PMI): refused
# before any work, nothing written; an sbatch script's plain run works
SLURM_STEP_NUM_TASKS=2 expect slurm-copies 'one of 2 tasks of a Slurm step.*srun --mpi=pmix' \
  'G0 X1\nM2\n' "${stock[@]}" "${tool[@]}"
PMI_SIZE=3 expect pmi-copies 'the launcher started 3 tasks \(PMI_SIZE\)' 'G0 X1\nM2\n' \
  "${stock[@]}" "${tool[@]}"
printf 'G0 X1\nM2\n' > "$dir/prog.ngc"
if SLURM_NTASKS=4 SLURM_JOB_ID=1 SLURM_STEP_NUM_TASKS=1 "$swarf" simulate "$dir/prog.ngc" \
    --out "$dir/out.vdb" --quiet "${stock[@]}" "${tool[@]}" && [ -f "$dir/out.vdb" ]; then
  pass=$((pass + 1))
else
  fail=$((fail + 1)); echo "FAIL sbatch-plain: a plain run inside an allocation must work"
fi
rm -f "$dir/out.vdb"
# absurd sizes: refused with the field, not simulated
expect tool-huge-d '--tool: D: 1e\+100 mm is beyond any cutter' 'G0 X1\n' "${stock[@]}" --tool T1=flat,D1e100
expect tool-tiny-d '--tool: D: the diameter 1e-09 mm is below 0.001 mm' 'G0 X1\n' "${stock[@]}" \
  --tool T1=flat,D1e-9
expect tool-negative-l '--tool: L: the length must be > 0 \(got -1\)' 'G0 X1\n' "${stock[@]}" \
  --tool T1=flat,D6,L-1
expect tool-huge-l '--tool: L: 1e\+300 mm is beyond' 'G0 X1\n' "${stock[@]}" --tool T1=vee,D6,A90,L1e300
printf 'T1 P1 D1e100 Z0\n' > "$dir-huge.tbl"
expect table-huge-d 'huge\.tbl:1.*diameter must be between 0.001 and 1000 mm' 'G0 X1\n' "${stock[@]}" \
  --tool-table "$dir-huge.tbl"
rm -f "$dir-huge.tbl"
expect output-folder-missing 'cannot write' 'G0 X1\n' "${stock[@]}" "${tool[@]}" --image "$dir/nothere/x.png"
# an error late in a program that already cut: still nothing written
expect late-error 'prog\.ngc:5:1:' 'G0 Z1\nG0 X5 Y5\nG1 Z-2 F100\nG1 X30\nW1\n' "${stock[@]}" "${tool[@]}"
# dialects: a name that is none, a Haas code read as LinuxCNC, a cycle grbl lacks
expect dialect-unknown '--dialect: give linuxcnc, fanuc, haas or grbl' 'G0 X1\n' "${stock[@]}" \
  "${tool[@]}" --dialect mach3
expect haas-as-linuxcnc 'prog\.ngc:2:1: Unknown m code used: M97' 'G0 X1\nM97 P10\n' "${stock[@]}" \
  "${tool[@]}"
expect grbl-cycle 'prog\.ngc:2:1: G81 is not a grbl code' 'G0 X1 Z5\nG81 X2 Z-1 R1 F100\n' \
  "${stock[@]}" "${tool[@]}" --dialect grbl

# swarf parse: notes on stderr, the block delete switch
printf 'G21 G0 X1\n/G0 X2\nM31\nM30\n' > "$dir/h.nc"
for bd in "" --block-delete; do
  want=$([ -z "$bd" ] && echo 2 || echo 1)
  out=$("$swarf" parse --quiet --dialect haas $bd "$dir/h.nc" 2> "$dir/stderr")
  if [ "$out" = "$dir/h.nc: $want moves" ] &&
     grep -q "h.nc:3:1: note: M31: chip auger forward: accepted, no motion" "$dir/stderr"; then
    pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL parse haas $bd: $out"; cat "$dir/stderr"; fi
done

# the program file itself is missing
rm -f "$dir"/out.*
"$swarf" simulate "$dir/missing.ngc" --out "$dir/out.vdb" "${stock[@]}" "${tool[@]}" 2> "$dir/stderr"
if [ $? -eq 2 ] && grep -q 'missing.ngc: cannot open' "$dir/stderr" && [ ! -e "$dir/out.vdb" ]; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL missing program file"; cat "$dir/stderr"; fi

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
