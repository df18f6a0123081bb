#!/usr/bin/env bash
# make-resolve-cases.sh — contact cases of real-mesh kind for `pdd resolve` (SPEC §11), made with
# Gmsh (scripts/meshes/*.geo) and TetGen (the thin plates), and the list of how each is run:
#   bash scripts/make-resolve-cases.sh DIR [--small]
# writes DIR/<case>-a.msh (and -b.msh) and DIR/cases.tsv, one case a line:
#   name <TAB> pdd resolve options <TAB> check-resolution.py options (the rigid comparison)
# scripts/run-resolve-cases.sh DIR runs them and prints the table. --small: coarser meshes
# (<= 5k elements a mesh) for a quick run. The cases (h: the mesh size):
#   ball-box     a ball (R 0.5) and a box, overlapping by one element layer (h); both move
#   plate-ball   a thin TetGen plate (2 x 2 x 0.08, fixed) and a ball (R 0.3) pushed h/2 into it
#   two-bodies   two balls in one file (--self), overlapping by one layer: two bodies, one mesh
#   coil         a bar wound 1.1 turns whose end presses one layer into its start (--self, one body)
#   large        two balls of about 10^5 elements each, one layer (0.06) deep (not with --small)
#   deep         a ball (R 0.3) pushed through the thin fixed plate: centre in the plate's mid-plane
# Reproducible: Gmsh with one thread, TetGen and the numpy maps are deterministic.
set -euo pipefail
D=${1:?usage: make-resolve-cases.sh DIR [--small]}
SMALL=0; [ "${2:-}" = "--small" ] && SMALL=1
cd "$(dirname "$0")/.."
G=scripts/meshes
PY=/usr/bin/python3
T="$PY $G/resolve_cases.py"
mkdir -p "$D"
gm() { gmsh -v 1 -nt 1 -3 "$@" -format msh41 -bin; }
if ((SMALL)); then h=0.11; hb=0.09; hc=0.1; pa=0.003; else h=0.05; hb=0.04; hc=0.05; pa=0.00005; fi

# The thin plate [-1, 1]^2 x [-0.08, 0] by TetGen (quality 1.4, largest volume pa).
cat > "$D/plate.poly" <<'POLY'
8 3 0 0
1 -1 -1 -0.08
2 1 -1 -0.08
3 1 1 -0.08
4 -1 1 -0.08
5 -1 -1 0
6 1 -1 0
7 1 1 0
8 -1 1 0
6 0
1
4 1 2 3 4
1
4 5 6 7 8
1
4 1 2 6 5
1
4 2 3 7 6
1
4 3 4 8 7
1
4 4 1 5 8
0
0
POLY
tetgen -pq1.4a$pa -Q "$D/plate.poly"
$T tetgen "$D/plate.1.ele" "$D/plate.msh"
rm -f "$D"/plate.1.*

: > "$D/cases.tsv"
row() { printf '%s\t%s\t%s\n' "$1" "$2" "$3" >> "$D/cases.tsv"; }

# ball-box: the box's face x = 0.5 - h lies one layer inside the ball.
gm $G/sphere.geo -setnumber R 0.5 -setnumber h $h -o "$D/ball-box-a.msh"
gm $G/box.geo -setnumber x0 "$($PY -c "print(0.5 - $h)")" -setnumber y0 -0.4 -setnumber z0 -0.4 \
   -setnumber dx 0.6 -setnumber dy 0.8 -setnumber dz 0.8 -setnumber h $h -o "$D/ball-box-b.msh"
row ball-box "--a $D/ball-box-a.msh --b $D/ball-box-b.msh" "--rigid-dir 1,0,0 --rigid-hi 1"

# plate-ball: the plate's top is z = 0; the ball's bottom at z = -hb/2.
cp "$D/plate.msh" "$D/plate-ball-a.msh"
gm $G/sphere.geo -setnumber R 0.3 -setnumber cz "$($PY -c "print(0.3 - $hb / 2)")" -setnumber h $hb \
   -o "$D/plate-ball-b.msh"
row plate-ball "--a $D/plate-ball-a.msh --b $D/plate-ball-b.msh --fix a" \
    "--fix a --rigid-dir 0,0,1 --rigid-hi 1"

# two-bodies: balls R 0.5 and 0.4, centres 0.9 - h apart, in one file.
gm $G/sphere.geo -setnumber R 0.5 -setnumber h $h -o "$D/two-bodies-1.msh"
gm $G/sphere.geo -setnumber R 0.4 -setnumber cx "$($PY -c "print(0.9 - $h)")" -setnumber cy 0.1 \
   -setnumber h $hb -o "$D/two-bodies-2.msh"
$T merge "$D/two-bodies-1.msh" "$D/two-bodies-2.msh" "$D/two-bodies-a.msh"
rm "$D/two-bodies-1.msh" "$D/two-bodies-2.msh"
row two-bodies "--a $D/two-bodies-a.msh --self" "--rigid-dir 1,0.1,0 --rigid-hi 1 --rigid-body 1"

# coil: a 0.3 x 0.3 bar, 1.1 turns of radius 1, rising 0.3 - hc a turn.
gm $G/box.geo -setnumber dx "$($PY -c "import math; print(2.2 * math.pi)")" -setnumber y0 -0.15 \
   -setnumber z0 -0.15 -setnumber dy 0.3 -setnumber dz 0.3 -setnumber h $hc -o "$D/coil-bar.msh"
$T bend "$D/coil-bar.msh" "$D/coil-a.msh" 1 "$($PY -c "print(0.3 - $hc)")"
rm "$D/coil-bar.msh"
row coil "--a $D/coil-a.msh --self" ""

# large: two unit balls (h 0.058, about 10^5 elements each), centres 1.94 apart.
if ((!SMALL)); then
  gm $G/sphere.geo -setnumber h 0.058 -o "$D/large-a.msh"
  gm $G/sphere.geo -setnumber cx 1.94 -setnumber cy 0.05 -setnumber h 0.058 -o "$D/large-b.msh"
  row large "--a $D/large-a.msh --b $D/large-b.msh" "--rigid-dir 1,0.05,0 --rigid-hi 1"
fi

# deep: the ball's centre in the plate's mid-plane z = -0.04 (through the plate).
cp "$D/plate.msh" "$D/deep-a.msh"
gm $G/sphere.geo -setnumber R 0.3 -setnumber cz -0.04 -setnumber h $hb -o "$D/deep-b.msh"
row deep "--a $D/deep-a.msh --b $D/deep-b.msh --fix a" "--fix a --rigid-dir 0,0,1 --rigid-hi 1"
rm "$D/plate.msh" "$D/plate.poly"

for f in "$D"/*.msh; do echo "make-resolve-cases: $f $($T count "$f" 2>/dev/null) tetrahedra" 2>/dev/null; done
