#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# modbus_rtu.sh SWARF FIXTURES -- the status map over Modbus RTU, on a
# pseudo-terminal pair made by socat (one end is swarf's serial line, the
# other mbpoll's): mbpoll -m rtu follows the running demo (state 1, progress
# never going back), garbage on the line and a request to another unit are
# ignored, and the final registers show 1000 per-mille and the lines, moves
# and removed volume of swarf's summary. Missing helpers fail the test.
set -u
swarf=$1 fixtures=$2
pass=0 fail=0
ok() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; fi; }
for p in socat mbpoll; do
  command -v $p > /dev/null || { echo "FAIL $p is missing: apt-get install $p (or tools/run test)"; exit 1; }
done
dir=$(mktemp -d)
spid= wpid=
trap '[ -n "$spid" ] && kill $spid 2>/dev/null; [ -n "$wpid" ] && kill $wpid 2>/dev/null; rm -rf "$dir"' EXIT

socat pty,raw,echo=0,link="$dir/line" pty,raw,echo=0,link="$dir/client" 2> "$dir/socat.log" &
spid=$!
for _ in $(seq 100); do [ -e "$dir/line" ] && [ -e "$dir/client" ] && break; sleep 0.05; done
ok "socat made the pty pair" '[ -e "$dir/line" ] && [ -e "$dir/client" ]'

"$swarf" simulate "$fixtures/demo.ngc" --stock box:0,0,-20,80,60,0 --tool T1=flat,D6,L24 \
  --tool T2=ball,D3.175,L20 --voxel 0.2 --out "$dir/r.vdb" \
  --modbus "rtu:$dir/line,19200,N,8,1,unit=3" --modbus-linger 6 > "$dir/summary" 2> "$dir/stderr" &
wpid=$!

# poll [mbpoll options...]: the values printed, one per line
poll() { mbpoll -m rtu -b 19200 -P none -o 1 -0 -1 "$@" "$dir/client" 2>&1 | sed -n 's/^\[[0-9]*\]:[[:space:]]*//p'; }

states=() progress=()
for _ in $(seq 600); do
  vals=($(poll -a 3 -t 3 -r 0 -c 2))
  if [ ${#vals[@]} -eq 2 ]; then
    states+=("${vals[0]}") progress+=("${vals[1]}")
    [ "${vals[0]}" -ge 2 ] && break
  fi
  sleep 0.05
done
echo "states ${states[*]}"
echo "per-mille ${progress[*]}"
ok "state 1 seen while running" 'printf "%s\n" "${states[@]}" | grep -qx 1'
ok "ended in state 2" '[ "${states[-1]}" = 2 ]'
ok "progress never goes back" 'printf "%s\n" "${progress[@]}" | sort -n -c'
ok "final progress 1000" '[ "${progress[-1]}" = 1000 ]'

printf 'garbage\x01\x03\xff\x00' > "$dir/client"
sleep 0.7
ok "other unit gets no answer" '[ -z "$(poll -a 4 -t 3 -r 0 -c 1)" ]'
moves=$(poll -a 3 -t 3:int -B -r 4 -c 1)
line=$(poll -a 3 -t 3:int -B -r 2 -c 1)
removed=$(poll -a 3 -t 4:int -B -r 8 -c 1)
done_bit=$(poll -a 3 -t 1 -r 1 -c 1)
ok "unmapped address answered with exception 02" \
  'mbpoll -m rtu -b 19200 -P none -o 1 -0 -1 -a 3 -t 3 -r 64 -c 1 "$dir/client" 2>&1 | grep -qi "illegal data address"'

wait $wpid
rc=$?
wpid=
cat "$dir/summary" "$dir/stderr"
ok "swarf exits 0" '[ $rc -eq 0 ]'
ok "moves = summary" '[ -n "$moves" ] && grep -q "moves $moves (" "$dir/summary"'
ok "line = lines read" '[ -n "$line" ] && grep -q "lines $line, " "$dir/summary"'
rep=$(sed -n 's/.*removed \([0-9.]*\) mm^3.*/\1/p' "$dir/summary")
ok "removed volume = summary" '[ -n "$removed" ] && awk -v a="$removed" -v b="$rep" "BEGIN { exit !(a - b <= 0.5 && b - a <= 0.5) }"'
ok "finished flag (discrete input 1)" '[ "$done_bit" = 1 ]'
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
