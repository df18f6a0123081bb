#!/usr/bin/env bash
# make-fixtures.sh — regenerate fixtures/families/*.json with `pdd generate`. The seeds and
# counts here are the record of how every shipped family file was made; the test
# `fixture_families_reproduce` regenerates them and compares bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
PDD=${PDD:-build/bin/pdd}
OUT=${1:-fixtures/families}
mkdir -p "$OUT"
while read -r family seed count; do
  "$PDD" generate --family "$family" --seed "$seed" --count "$count" --output "$OUT/$family.json"
done <<'LIST'
paper 1 12
nested 1 4
parallel-edges 1 4
colinear-edges 1 4
coplanar-faces 1 4
shared-vertex 1 3
shared-edge 1 3
shared-face 1 3
identical 1 3
touching 1 3
disjoint 1 3
near-touching 1 4
scaled-large 3 3
scaled-small 4 3
sliver 1 4
undecidable-optimum 2 3
closed-form 1 6
near-coplanar 1 8
adversarial 1 30
aligned 1 24
rounding-contacts 1 12
LIST
