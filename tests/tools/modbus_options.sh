#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# modbus_options.sh SWARF -- bad --modbus options: each must exit 2 before
# any work, name the flag and say what to give; --help documents them.
set -u
swarf=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"; [ -n "${lpid:-}" ] && kill $lpid 2>/dev/null' EXIT
pass=0 fail=0
printf 'G0 X1\n' > "$dir/p.ngc"
expect() { # NAME REGEX options...
  local name=$1 regex=$2
  shift 2
  "$swarf" simulate "$dir/p.ngc" --stock box:0,0,-5,10,10,0 --tool T1=ball,D2 --out "$dir/o.vdb" \
    --quiet "$@" > /dev/null 2> "$dir/err"
  local rc=$?
  if [ $rc -eq 2 ] && grep -qE -- "$regex" "$dir/err" && [ ! -e "$dir/o.vdb" ]; then
    pass=$((pass + 1))
  else
    fail=$((fail + 1)); echo "FAIL $name: exit $rc"; cat "$dir/err"
  fi
}
expect no-kind '--modbus: .*give tcp:HOST:PORT or rtu:' --modbus udp:1:2
expect bad-port '--modbus: .*give tcp' --modbus tcp:127.0.0.1:99999
expect bad-unit '--modbus: .*unit=1..247' --modbus tcp:127.0.0.1:0,unit=300
expect bad-rtu '--modbus: .*rtu:DEVICE,BAUD' --modbus rtu:/dev/null,19200,X,8,1
expect no-device 'cannot open /nonexistent' --modbus rtu:/nonexistent/tty,19200,N,8,1
expect push-no-address '--modbus-push: .*address=A' --modbus-push tcp:127.0.0.1:1502,unit=1
expect push-rtu '--modbus-push: ' --modbus-push rtu:/dev/null,19200,N,8,1,address=0
expect linger-alone 'give --modbus or --modbus-push' --modbus-linger 3
expect linger-bad '--modbus-linger: give 0 to 86400' --modbus tcp:127.0.0.1:0 --modbus-linger -1
expect commands-push '--modbus-commands: ' --modbus-commands --modbus-push tcp:127.0.0.1:1502,unit=1,address=0
expect no-value '--modbus: needs a value' --modbus
# a port already in use is reported before the job starts
/usr/bin/python3 -c 'import socket,sys,time
s=socket.socket(); s.bind(("127.0.0.1",0)); s.listen(); print(s.getsockname()[1], flush=True); time.sleep(30)' > "$dir/port" &
lpid=$!
for _ in $(seq 100); do [ -s "$dir/port" ] && break; sleep 0.05; done
expect busy-port 'cannot listen on 127.0.0.1:[0-9]+: .*choose another port' --modbus "tcp:127.0.0.1:$(cat "$dir/port")"
if "$swarf" simulate --help | grep -q -- '--modbus rtu:DEVICE' && "$swarf" simulate --help | grep -q -- '--modbus-commands'; then
  pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL --help does not document --modbus"; fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
