#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# style_format.sh SRC -- every C and C++ source of the tree laid out as
# .clang-format says (clang-format 14, Debian 12's): a file that differs
# fails the test with its name; `clang-format -i FILE` lays it out. SKIPPED
# (exit 77) where clang-format is not installed (tools/run test installs it).
src=${1:?usage: style_format.sh SRC}
command -v clang-format > /dev/null 2>&1 || {
  echo "SKIPPED: clang-format is not installed (apt-get install clang-format)"
  exit 77
}
cd "$src" || exit 2
n=0 bad=0
for f in $(find engine toolpath gcode stock tests tools -name '*.c' -o -name '*.h' -o -name '*.cc' | sort); do
  n=$((n + 1))
  if ! clang-format --dry-run --Werror "$f" > /dev/null 2>&1; then
    echo "not laid out by clang-format: $f"
    bad=$((bad + 1))
  fi
done
echo "$n files, $bad not laid out ($(clang-format --version | head -1))"
[ "$bad" -eq 0 ]
