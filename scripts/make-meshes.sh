#!/usr/bin/env bash
# make-meshes.sh — write the test meshes of fixtures/meshes/ with Gmsh (Debian package `gmsh`,
# 4.8.4 in Debian 12), from the geometry scripts in scripts/meshes/*.geo. Reproducible: one
# thread (-nt 1), fixed parameters; the same Gmsh version writes the same files.
#   bash scripts/make-meshes.sh            the small shipped meshes (fixtures/meshes/)
#   bash scripts/make-meshes.sh --large D  two unit balls of about 10^5 tetrahedra each whose
#                                          centres are 1.9 apart (a shallow lens of overlap), in
#                                          D/ (for `pdd bench mesh --a D/large-a.msh --b
#                                          D/large-b.msh`; not shipped)
# Several formats on purpose: the readers (mesh/) are tested on files Gmsh itself wrote, in
# MSH 2.2 and 4.1, ASCII and binary, and legacy VTK, ASCII and binary.
set -euo pipefail
cd "$(dirname "$0")/.."
G=scripts/meshes
gm() { gmsh -v 1 -nt 1 -3 "$@"; }

if [ "${1:-}" = "--large" ]; then
  D=${2:?usage: make-meshes.sh --large DIR}
  mkdir -p "$D"
  gm $G/sphere.geo -setnumber h 0.058 -format msh41 -bin -o "$D/large-a.msh"
  gm $G/sphere.geo -setnumber cx 1.9 -setnumber cy 0.1 -setnumber h 0.058 -format msh41 -bin \
     -o "$D/large-b.msh"
  exit 0
fi

O=fixtures/meshes
mkdir -p $O/bad
# Two overlapping balls; ball A in every format the readers take.
gm $G/sphere.geo -format msh41 -o $O/sphere-a.msh
gm $G/sphere.geo -format msh41 -bin -o $O/sphere-a.bin41.msh
gm $G/sphere.geo -format msh22 -o $O/sphere-a.v22.msh
gm $G/sphere.geo -format msh22 -bin -o $O/sphere-a.bin22.msh
gm $G/sphere.geo -format vtk -o $O/sphere-a.vtk
gm $G/sphere.geo -format vtk -bin -o $O/sphere-a.bin.vtk
gm $G/sphere.geo -setnumber cx 1.1 -setnumber cy 0.35 -setnumber cz 0.2 -setnumber R 0.9 \
   -format msh22 -bin -o $O/sphere-b.msh
# A torus through a box.
gm $G/torus.geo -format msh41 -bin -o $O/torus.msh
gm $G/box.geo -setnumber x0 0.7 -setnumber y0 -0.3 -setnumber z0 -0.5 -setnumber dx 0.6 \
   -setnumber dy 0.6 -setnumber dz 1 -setnumber h 0.2 -format vtk -o $O/box.vtk
# A mesh with slivers (Delaunay, no optimisation), to meet ball A.
gm $G/slivers.geo -setnumber x0 0.5 -setnumber y0 -0.4 -setnumber z0 -0.4 -format msh22 \
   -o $O/slivers.msh
# Touching meshes: two boxes sharing the plane x = 1, meshed independently (non-conforming
# face), and the same two boxes meshed together (conforming interface).
gm $G/box.geo -setnumber h 0.4 -format msh41 -o $O/touching-a.msh
gm $G/box.geo -setnumber x0 1 -setnumber h 0.3 -format msh41 -o $O/touching-b.msh
gm $G/conforming.geo -setnumber part 1 -format msh41 -o $O/conforming-a.msh
gm $G/conforming.geo -setnumber part 2 -format msh41 -o $O/conforming-b.msh
# Self-contact: two balls meshed independently in one file.
gm $G/two-spheres.geo -format msh22 -o $O/two-spheres.msh
# Tiny meshes for the exact engine: two coarse unit cubes, one shifted and rotated a little.
gm $G/box.geo -setnumber h 1 -format msh22 -o $O/tiny-a.msh
gm $G/box.geo -setnumber x0 0.6 -setnumber y0 0.3 -setnumber z0 0.2 -setnumber h 1 -format msh41 \
   -o $O/tiny-b.msh

# Bad meshes (fixtures/meshes/bad/): cut from the good ones, so their messages can be checked.
head -c 4000 $O/sphere-a.msh > $O/bad/truncated.msh
head -c 3000 $O/sphere-a.bin41.msh > $O/bad/truncated.bin41.msh
head -c 3000 $O/sphere-a.bin22.msh > $O/bad/truncated.bin22.msh
head -c 3000 $O/sphere-a.vtk > $O/bad/truncated.vtk
echo "make-meshes: wrote $(ls $O/*.msh $O/*.vtk | wc -l) meshes to $O"
