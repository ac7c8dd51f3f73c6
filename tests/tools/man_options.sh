#!/bin/bash
# SPDX-License-Identifier: MPL-2.0
# man_options.sh SWARF MANPAGE SRC -- the command's options, its --help and its
# man page agree:
#   - every option `swarf help COMMAND` names is in swarf.1 (made from them);
#   - every option the command's parsers compare against (a "--name" string in
#     tools/cli/ and tools/modbus/) is named by some command's help, so no
#     option is accepted that --help and the man page do not explain;
#   - every command `swarf --help` lists has its own section in the page.
set -u
swarf=$1 man=$2 src=$3
[ -s "$man" ] || { echo "FAIL: no man page at $man"; exit 1; }
page=$(sed -e 's/\\-/-/g' -e 's/\\e/\\/g' "$man")
commands=$(("$swarf" --help) | sed -n '/^commands:/,/^$/p' | awk '/^  [a-z]/ {print $1}' |
  grep -v '^help$' | sort -u)
[ -n "$commands" ] || { echo "FAIL: no commands in swarf --help"; exit 1; }
bad=0 all=""
for c in $commands; do
  help=$("$swarf" help "$c") || { echo "FAIL: swarf help $c failed"; exit 1; }
  printf '%s\n' "$page" | grep -q "usage: swarf $c" || { echo "FAIL: swarf.1 lacks $c"; bad=1; }
  flags=$(printf '%s\n' "$help" | grep -o -- '--[a-z][a-z0-9-]*' | sort -u)
  for f in $flags; do
    printf '%s\n' "$page" | grep -q -- "$f" || { echo "FAIL: $c's $f is not in swarf.1"; bad=1; }
  done
  echo "$c: $(echo $flags | wc -w) options in --help, all in swarf.1"
  all="$all $(echo $flags) --help"
done
parsed=$(grep -ho '"--[a-z][a-z0-9-]*"' "$src"/tools/cli/*.c "$src"/tools/modbus/*.c | tr -d '"' |
  sort -u)
n=0
for f in $parsed; do
  n=$((n + 1))
  case " $all " in *" $f "*) ;; *) echo "FAIL: $f is parsed but no --help names it"; bad=1 ;; esac
done
echo "$n options parsed in tools/cli and tools/modbus, each named by a command's --help"
exit $bad
