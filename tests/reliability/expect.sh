#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# expect.sh STATUS PATTERN CMD...: a reproducer of ../shared/reliability as a
# test. Runs CMD and passes when it exits with STATUS and its output (stdout
# and stderr) matches the extended regular expression PATTERN. The hang
# limit is ctest's TIMEOUT (generous: this is not a benchmark).
want=$1 pattern=$2
shift 2
out=$("$@" 2>&1)
got=$?
if [ "$got" != "$want" ]; then
  printf 'FAIL: exit %s, expected %s: %s\n%s\n' "$got" "$want" "$*" "$out" | head -c 4000
  exit 1
fi
if ! printf '%s\n' "$out" | grep -Eq -- "$pattern"; then
  printf 'FAIL: output does not match /%s/: %s\n%s\n' "$pattern" "$*" "$out" | head -c 4000
  exit 1
fi
printf 'ok: exit %s, /%s/\n' "$got" "$pattern"
