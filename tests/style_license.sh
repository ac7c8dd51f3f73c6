#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# style_license.sh SRC -- swarf is under the Mozilla Public License 2.0
# (LICENSE; compatible with OpenVDB's MPL-2.0 and the LGPL of FLINT and
# libmodbus): LICENSE holds its text, and every source file (C, C++, the
# tables they include, Python, shell, CMake, the page's HTML and JavaScript,
# the scripts without an extension) names it on an SPDX line within its first
# three lines. A file without one fails the test with its name. The fixtures
# and test data (programs, tables, seeds) carry their own terms
# (fixtures/SOURCES.md).
src=${1:?usage: style_license.sh SRC}
cd "$src" || exit 2
bad=0 n=0
grep -q "^Mozilla Public License Version 2.0" LICENSE 2> /dev/null || {
  echo "LICENSE does not hold the Mozilla Public License 2.0"
  bad=1
}
for f in CMakeLists.txt .ci/run $(find engine toolpath gcode stock tests tools -type f \
  \( -name '*.c' -o -name '*.h' -o -name '*.cc' -o -name '*.def' -o -name '*.map' \
  -o -name '*.py' -o -name '*.sh' -o -name '*.cmake' -o -name 'CMakeLists.txt' -o -name '*.in' \
  -o -name '*.js' -o -name '*.html' -o -path 'tools/run' -o -path 'tools/bench/bench*' \) \
  -not -path '*_seeds/*' -not -path '*/__pycache__/*' | sort); do
  n=$((n + 1))
  if ! head -n 3 "$f" | grep -q "SPDX-License-Identifier: MPL-2.0"; then
    echo "no SPDX-License-Identifier line: $f"
    bad=$((bad + 1))
  fi
done
echo "$n source files, $bad without the SPDX line"
[ "$bad" -eq 0 ]
