#!/bin/bash
# SPDX-License-Identifier: MPL-2.0
# cli_envelope.sh -- `swarf envelope` against the paper's Example 2 (eq. 19, 20,
# 22 and ENVELOPE.md's Delta and branch points), its CSV against the curve's
# equations (f = 0, |n| = 1, Z = 2z^3 - 3z on this surface), and its errors.
# Usage: cli_envelope.sh SWARF
swarf=$1
fail=0
check() { if ! grep -qF -- "$2" <<<"$1"; then echo "missing: $2"; fail=1; fi; }

out=$("$swarf" envelope --qss 1,-1,0,0,0,0 --axis 2,1,2 --tdot 1,1,0 --half-angle 2 --exact \
      --at-z 1/2,-3/4 --points 40) || { echo "exit status $?"; exit 1; }
check "$out" "v: 1, -3/5, 4/5"
check "$out" "f: -4/3*x*z + 8/3*y*z + x - 3/5*y + 4/5*z"          # eq. 19 / 15
check "$out" "P: (-15/73 + 77/292*sqrt(6), -33/73 - 35/292*sqrt(6), 1/2)"   # eq. 20
check "$out" "deg k, l, m: 2, 4, 3"
check "$out" "D: 5032323912*s^3 + (7806587880 + 7828867480*sqrt(6))*s^2 + (46260368554 + 4537170456*sqrt(6))*s + (24121304410 + 10293044615*sqrt(6))"
check "$out" "Delta(z) primitive: 1000*z^4-660*z^3-775*z^2+660*z-153"
check "$out" "z1 = [-0.98015913027410"
check "$out" "z2 = [0.91895735560411"
check "$out" "components: 1"
check "$out" "fast: components 1"
check "$out" "fast: branch points -0.980159130274109 0.918957355604119"
check "$out" "Theorem 2 identity: holds"
rows=$(sed -n '/^z,branch,nx/,$p' <<<"$out" | tail -n +2)
n=$(wc -l <<<"$rows")
[ "$n" -eq 84 ] || { echo "expected 84 CSV rows (2 + 2 slices + 40 x 2), got $n"; fail=1; }
bad=$(awk -F, '{ x=$3; y=$4; z=$5; f=15*x-20*x*z-9*y+40*y*z+12*z; g=x*x+y*y+z*z-1; Z=2*z^3-3*z;
        if (f>1e-12||f<-1e-12||g>1e-12||g<-1e-12||$8-Z>1e-12||Z-$8>1e-12) print }' <<<"$rows")
[ -z "$bad" ] || { echo "rows off the curve: $bad"; fail=1; }
# fast path rows agree with the exact ones at the same slices
fast=$("$swarf" envelope --qss 1,-1,0,0,0,0 --axis 2,1,2 --tdot 1,1,0 --half-angle 2 --at-z 1/2 |
       sed -n '/^z,branch/,$p' | tail -n +2)
ex=$(head -2 <<<"$rows")
d=$(paste -d, <(echo "$fast") <(echo "$ex") | awk -F, '{ m=0; for (i=3;i<=11;i++) { e=$i-$(i+11);
      if (e<0) e=-e; if (e>m) m=e } print m }' | sort -g | tail -1)
awk -v d="$d" 'BEGIN { exit !(d < 1e-12) }' || { echo "fast and exact slices differ by $d"; fail=1; }

expect2() {
  local msg
  msg=$("$swarf" envelope "$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -ne 2 ]; then echo "exit $rc (want 2) for: $*"; fail=1; fi
  if [ -z "$msg" ]; then echo "no message for: $*"; fail=1; fi
}
base=(--qss 1,-1,0,0,0,0 --tdot 1,1,0)
expect2 "${base[@]}" --axis 2,1,2 --half-angle abc
expect2 "${base[@]}" --axis 1,1,0 --half-angle 2 --exact
expect2 "${base[@]}" --axis 0,0,0 --half-angle 2
expect2 "${base[@]}" --axis 2,1 --half-angle 2
expect2 "${base[@]}" --axis 2,1,2 --half-angle 2 --at-z 3/2
expect2 "${base[@]}" --axis 2,1,2 --half-angle 2 --points 0
expect2 "${base[@]}" --axis 2,1,2 --half-angle 1/0
expect2 --qss 1,2 --axis 2,1,2 --tdot 1,1,0 --half-angle 2
expect2 "${base[@]}" --axis 2,1,2
# degenerate cases are named, not crashed on
out=$("$swarf" envelope --qss 1,2,0,0,0,0 --axis 0,0,1 --tdot 0,0,0 --half-angle 1 --exact) || fail=1
check "$out" "case: spin about the own axis"
out=$("$swarf" envelope --qss 1,1,0,0,0,2 --axis 2,1,2 --tdot 0,0,0 --half-angle 1 --exact) || fail=1
check "$out" "case: whole sphere"
out=$("$swarf" envelope --qss 1,2,0,0,0,0 --axis 0,0,1 --tdot 1,0,0 --half-angle 1 --exact) || fail=1
check "$out" "Delta roots in [-1, 1]: 2"

# --tool: any cutter's curve at the instant; every row meets the characteristic
# condition (v + omega x X) . n = 0 with the printed v and omega, and lies on the
# drawn V-bit (cone r = z up to 3, cylinder r = 3, top face z = 24).
out=$("$swarf" envelope --tool vee,D6,A90 --axis 2,1,2 --tdot 1,1,0 --half-angle 2 --points 60) ||
  { echo "--tool: exit status $?"; fail=1; }
check "$out" "tool: vee D6 L24"
check "$out" "fast: components 2"
v=$(sed -n 's/^v: //p' <<<"$out"); w=$(sed -n 's/^omega: //p' <<<"$out")
rows=$(sed -n '/^z,branch,nx/,$p' <<<"$out" | tail -n +2)
[ "$(wc -l <<<"$rows")" -eq 120 ] || { echo "--tool: expected 120 rows"; fail=1; }
bad=$(awk -F, -v v="$v" -v w="$w" 'BEGIN { split(v, V, ", "); split(w, W, ", ") }
  { nx=$3; ny=$4; nz=$5; X=$6; Y=$7; Z=$8;
    cx=W[2]*Z-W[3]*Y; cy=W[3]*X-W[1]*Z; cz=W[1]*Y-W[2]*X;
    f=(V[1]+cx)*nx+(V[2]+cy)*ny+(V[3]+cz)*nz; r=sqrt(X*X+Y*Y);
    on=(Z<=3+1e-9 && (r-Z<1e-9 && Z-r<1e-9)) || (r-3<1e-9 && 3-r<1e-9) || (Z-24<1e-9 && 24-Z<1e-9 && r<=3+1e-9);
    if (f>1e-9||f<-1e-9||!on) print }' <<<"$rows")
[ -z "$bad" ] || { echo "--tool rows off the curve or the V-bit: $bad"; fail=1; }
out=$("$swarf" envelope --tool T4=qss,1,-1,0,0 --axis 2,1,2 --tdot 1,1,0 --half-angle 2) ||
  { echo "--tool qss: exit status $?"; fail=1; }
check "$out" "tool: qss"
expect2 --tool vee,D6 --axis 2,1,2 --tdot 1,1,0 --half-angle 2
expect2 --tool vee,D6,A90 --qss 1,-1,0,0,0,0 --axis 2,1,2 --tdot 1,1,0 --half-angle 2
expect2 --tool vee,D6,A90 --axis 2,1,2 --tdot 1,1,0 --half-angle 2 --exact
exit $fail
