#!/bin/bash
# SPDX-License-Identifier: MPL-2.0
# grid_digests.sh SWARF SRC REAL -- the grids of a few whole programs are the
# ones recorded in tests/tools/grid_digests.txt (SHA-256 of the .vdb after its
# 57-byte header, which holds a random UUID), with one thread and with two.
# A change that is meant to keep the outputs (speed, refactoring) must keep
# these; one that changes them on purpose records the new digests in the
# same commit, saying why. Rows whose program lives in ../shared are SKIPPED
# without it; the demo's row always runs. Columns: name, program (real:FILE
# in ../shared/conformance/real, fixtures:FILE), stock, tools (joined by +),
# voxel, digest.
set -u
swarf=$1 src=$2 real=$3
table=$src/tests/tools/grid_digests.txt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ran=0 bad=0
while read -r name program stock tool voxel digest; do
  case "$name" in '#'* | '') continue ;; esac
  path=${program/#real:/$real/}
  path=${path/#fixtures:/$src/fixtures/}
  if [ ! -f "$path" ]; then
    echo "$name: SKIPPED ($path is not here: it lives in ../shared beside a checkout)"
    continue
  fi
  tools=()
  IFS=+ read -r -a specs <<< "$tool"
  for x in "${specs[@]}"; do tools+=(--tool "$x"); done
  for t in 1 2; do
    "$swarf" simulate "$path" --stock "$stock" "${tools[@]}" --voxel "$voxel" --threads $t \
      --out "$tmp/$name.vdb" --quiet || { echo "FAIL: $name: swarf exited $?"; bad=1; continue; }
    got=$(tail -c +58 "$tmp/$name.vdb" | sha256sum | cut -d' ' -f1)
    if [ "$got" = "$digest" ]; then
      echo "$name, $t thread(s): the recorded grid"
    else
      echo "FAIL: $name, $t thread(s): digest $got, recorded $digest"
      bad=1
    fi
  done
  ran=$((ran + 1))
done < "$table"
[ "$ran" -gt 0 ] || { echo "FAIL: no row ran"; exit 1; }
exit $bad
