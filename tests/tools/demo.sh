#!/usr/bin/env bash
# SPDX-License-Identifier: MPL-2.0
# demo.sh SWARF FIXTURES -- the bundled demo end to end: it runs, writes the
# three files, and the .vdb reloads (in swarf and, when present, in Debian's
# pyopenvdb, an independent reader) with the active voxel count and voxel size
# that the simulation reported.
set -u
swarf=$1 fixtures=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL $1"; fi; }

"$swarf" simulate "$fixtures/demo.ngc" --stock box:0,0,-20,80,60,0 \
  --tool T1=flat,D6,L24 --tool T2=ball,D3.175,L20 --voxel 0.25 \
  --out "$dir/remaining.vdb" --mesh "$dir/remaining.stl" --image "$dir/remaining.png" \
  > "$dir/summary" 2> "$dir/stderr"
rc=$?
cat "$dir/summary" "$dir/stderr"
ok "demo exits 0" '[ $rc -eq 0 ]'
ok "vdb written" '[ -s "$dir/remaining.vdb" ]'
ok "png written" '[ "$(head -c 8 "$dir/remaining.png" | od -An -tx1 | tr -d " \n")" = 89504e470d0a1a0a ]'
ntri=$(sed -n 's/.*remaining.stl (\([0-9]*\) triangles).*/\1/p' "$dir/summary")
size=$(stat -c %s "$dir/remaining.stl" 2>/dev/null || echo 0)
ok "stl size matches its triangle count" '[ -n "$ntri" ] && [ "$size" -eq $((84 + 50 * ntri)) ] && [ "$ntri" -gt 1000 ]'
active=$(sed -n 's/.*active voxels \([0-9]*\).*/\1/p' "$dir/summary")
"$swarf" info "$dir/remaining.vdb" > "$dir/info"
cat "$dir/info"
ok "reloads with the same active voxel count" '[ -n "$active" ] && grep -qx "active_voxels $active" "$dir/info"'
ok "reloaded grid is a valid level set" 'grep -qx "level_set valid" "$dir/info"'
ok "removed volume is positive" 'grep -qE "removed [1-9][0-9]*\.[0-9] mm\^3" "$dir/summary"'
if /usr/bin/python3 -c 'import pyopenvdb' 2>/dev/null; then
  /usr/bin/python3 - "$dir/remaining.vdb" "$active" <<'PY'
import sys, pyopenvdb as vdb
grid = vdb.read(sys.argv[1], "stock")
assert grid.gridClass == vdb.GridClass.LEVEL_SET, grid.gridClass
assert abs(grid.transform.voxelSize()[0] - 0.25) < 1e-9, grid.transform.voxelSize()
assert grid.activeVoxelCount() == int(sys.argv[2]), (grid.activeVoxelCount(), sys.argv[2])
assert abs(grid.background - 0.75) < 1e-6, grid.background
print("pyopenvdb: stock, level set, voxel 0.25, %d active voxels" % grid.activeVoxelCount())
PY
  ok "pyopenvdb reads it" '[ $? -eq 0 ]'
else
  echo "pyopenvdb not installed: independent reader skipped"
fi
echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
