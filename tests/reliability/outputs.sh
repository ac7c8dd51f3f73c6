#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# outputs.sh SWARF P10000: the output rules of ../shared/reliability
# (README "Outputs"), run in a scratch folder (as root in CI: a rename onto a
# device, FIFO or symlink would succeed there). P10000 is the 10,000-turn
# helix program (once minutes, now about a second): refused before any work.
swarf=$1 slow=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 1
pass=0 fail=0
ok() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; cat err 2>/dev/null; fi; }
S="--stock box:0,0,-10,40,40,0 --tool T1=ball,D3 --voxel 0.5 --quiet"
printf 'G21 G0 X0 Y0 Z1\nG1 Z-1 F100\nG1 X30 Y20\nM30\n' > p.ngc
cp p.ngc p.orig
# Refused before any work (the slow program would run for minutes), naming the flag.
for bad in "." "sub/" ""; do
  "$swarf" simulate "$slow" $S --out "$bad" 2> err
  ok "--out \"$bad\" refused before the run" '[ $? -eq 2 ] && grep -q -- "--out: cannot write" err'
done
"$swarf" simulate p.ngc $S --out p.ngc 2> err
ok "the program as --out refused, unchanged" '[ $? -eq 2 ] && grep -q "is the input PROGRAM" err && cmp -s p.ngc p.orig'
"$swarf" simulate p.ngc $S --out a.vdb --report a.vdb 2> err
ok "one file for two outputs refused" '[ $? -eq 2 ] && grep -q "is also the output of --out" err && [ ! -e a.vdb ]'
# A symlink as --mesh: refused, the link and its target untouched.
echo target > t.stl
ln -s t.stl link.stl
"$swarf" simulate p.ngc $S --out o.vdb --mesh link.stl 2> err
ok "a symlink as --mesh refused" '[ $? -eq 2 ] && [ -L link.stl ] && [ "$(cat t.stl)" = target ] && [ ! -e o.vdb ]'
# A FIFO as --mesh: written into (the reader gets a whole binary STL), still a FIFO.
mkfifo f.stl
(cat f.stl > from-fifo.stl) &
reader=$!
"$swarf" simulate p.ngc $S --out o.vdb --mesh f.stl 2> err
rc=$?
wait $reader
ok "a FIFO as --mesh is written into" '[ $rc -eq 0 ] && [ -p f.stl ] && [ $(wc -c < from-fifo.stl) -gt 84 ]'
# A character device: --out /dev/null discards, /dev/null stays a device.
"$swarf" simulate p.ngc $S --out /dev/null 2> err
ok "--out /dev/null discards" '[ $? -eq 0 ] && [ -c /dev/null ]'
# All outputs or none: the mesh cannot be written (file size limit), the old .vdb stays.
cp o.vdb old.vdb
printf 'G21 G0 X0 Y0 Z1\nG1 Z-2 F100\nG1 X35 Y30\nM30\n' > q.ngc
sh -c "trap '' XFSZ; ulimit -f 1000; exec \"$swarf\" simulate q.ngc $S --out o.vdb --mesh big.stl" 2> err
ok "all or none: a failed mesh keeps the old .vdb" '[ $? -eq 1 ] && cmp -s o.vdb old.vdb && [ ! -e big.stl ]'
ok "no temporary after the failure" '[ -z "$(ls | grep "\.tmp\.")" ]'
# The report is one of the outputs: a failed mesh keeps the old report, a
# failed report keeps the old .vdb and mesh (its folder's file size limit:
# the report of a 20000-line program is ~2 MB, its .vdb and mesh < 1 MB).
"$swarf" simulate p.ngc $S --out o.vdb --report r.json 2> err
cp r.json old.json
cp o.vdb old.vdb
sh -c "trap '' XFSZ; ulimit -f 1000; exec \"$swarf\" simulate q.ngc $S --out o.vdb --mesh big.stl --report r.json" 2> err
ok "all or none: a failed mesh keeps the old report" '[ $? -eq 1 ] && cmp -s r.json old.json && cmp -s o.vdb old.vdb && [ ! -e big.stl ]'
awk 'BEGIN { print "G21 G0 X0 Y0 Z1"; print "G1 Z-1 F100"; for (i = 0; i < 20000; i++) printf "G1 X%d Y2\n", (i % 2) * 5 + 2; print "M30" }' > many.ngc
sed 's/Z-1 F100/Z-2 F100/' many.ngc > many2.ngc
M="--stock box:0,0,-5,10,10,0 --tool T1=ball,D3 --voxel 0.5 --quiet"
"$swarf" simulate many.ngc $M --out m.vdb --mesh m.stl --report m.json 2> err
cp m.vdb old-m.vdb
cp m.stl old-m.stl
cp m.json old-m.json
sh -c "trap '' XFSZ; ulimit -f 3000; exec \"$swarf\" simulate many2.ngc $M --out m.vdb --mesh m.stl --report m.json" 2> err
ok "all or none: a failed report keeps the old .vdb, mesh and report" '[ $? -eq 1 ] && grep -q "m.json: cannot write the report" err && cmp -s m.vdb old-m.vdb && cmp -s m.stl old-m.stl && cmp -s m.json old-m.json'
"$swarf" simulate many2.ngc $M --out m.vdb --mesh m.stl --report m.json 2> err
ok "the same run without the limit writes all three" '[ $? -eq 0 ] && ! cmp -s m.vdb old-m.vdb && ! cmp -s m.stl old-m.stl && ! cmp -s m.json old-m.json'
"$swarf" simulate p.ngc $S --out o.vdb --report no-such-folder/r.json 2> err
ok "--report in a missing folder refused before the run" '[ $? -eq 2 ] && grep -q -- "--report: cannot write" err'
ok "no temporary after the report failures" '[ -z "$(ls | grep "\.tmp\.")" ]'
# kill -9, SIGTERM and SIGINT during runs that write (finer voxel: a longer
# write): no temporary left. A background job of a script starts with SIGINT
# ignored, which swarf keeps (as under nohup): env --default-signal gives it
# the default back, or the INT runs would go to their end unkilled.
K="--stock box:0,0,-10,40,40,0 --tool T1=ball,D3 --voxel 0.08 --quiet"
killed_late=""
for sig in KILL TERM INT; do
  for delay in 0.3 0.8 1.5 2.5; do
    env --default-signal=INT "$swarf" simulate q.ngc $K --out k.vdb --mesh k.stl 2> /dev/null &
    pid=$!
    sleep $delay
    kill -$sig $pid 2> /dev/null
    wait $pid 2> /dev/null
    rc=$?
    [ $rc -gt 128 ] || killed_late="$killed_late $sig@$delay:$rc"
  done
  ok "no temporary after kill -$sig" '[ -z "$(ls | grep "\.tmp\.")" ]'
done
# Each run was still going when its signal came (it ended by the signal).
ok "every run ended by its signal (${killed_late:-all})" '[ -z "$killed_late" ]'
# A stale temporary of a dead swarf is swept by the next write there.
sh -c 'exit 0' &
dead=$!
wait $dead
echo stale > "o.vdb.swarf.tmp.$dead"
echo mine > "o.vdb.tmp.$dead"
"$swarf" simulate p.ngc $S --out o.vdb 2> err
ok "a dead process's temporary is swept" '[ $? -eq 0 ] && [ ! -e "o.vdb.swarf.tmp.$dead" ]'
# a user's own file named like an old temporary is never removed
ok "a user's o.vdb.tmp.N is kept" '[ "$(cat "o.vdb.tmp.$dead")" = mine ]'
rm -f "o.vdb.tmp.$dead"
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
