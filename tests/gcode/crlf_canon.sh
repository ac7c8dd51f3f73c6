#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# crlf_canon.sh SWARF -- a CRLF program's `swarf parse --canon`: the CR ends
# the line, so no call carries it (a `;` comment's text was printed with a raw
# CR before its closing quote); the calls are those of the same program with
# LF endings.
set -u
swarf=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf 'G21 G90\r\n(a comment)\r\n; a semicolon comment\r\nG0 X1 (MSG, a message)\r\nG1 X2 F100 ; feed\r\nM2\r\n' \
  > "$dir/crlf.ngc"
tr -d '\r' < "$dir/crlf.ngc" > "$dir/lf.ngc"
"$swarf" parse --canon "$dir/crlf.ngc" > "$dir/crlf.out" || { echo "FAIL: parse --canon exit $?"; exit 1; }
"$swarf" parse --canon "$dir/lf.ngc" > "$dir/lf.out" || { echo "FAIL: the LF program"; exit 1; }
fail=0
if tr -d '\n' < "$dir/crlf.out" | grep -q "$(printf '\r')"; then
  echo "FAIL: a raw CR in the output:"; grep -n "$(printf '\r')" "$dir/crlf.out" | cat -A; fail=1
fi
grep -q 'COMMENT("a semicolon comment")' "$dir/crlf.out" || { echo "FAIL: the ; comment's text"; fail=1; }
cmp -s "$dir/crlf.out" "$dir/lf.out" || { echo "FAIL: CRLF and LF differ:"; diff "$dir/lf.out" "$dir/crlf.out"; fail=1; }
[ $fail -eq 0 ] && echo "CRLF: $(wc -l < "$dir/crlf.out") canon calls, no CR, the same as with LF"
exit $fail
