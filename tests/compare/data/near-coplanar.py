# near-coplanar.py — writes near-coplanar.json (beside it, or argv[1]): near-coplanar contacts,
# a face of B ~1e-12 (1e-15 .. 1e-11) inside a face of A, tetrahedra of size ~8, the resting
# contacts meshes have everywhere. Kinds: B's face parallel to A's (flat), or tilted by a small
# angle about an axis in the face plane through B's face centroid (part of the face out of
# contact); A's face in z = 0 or y = 0 (coordinate planes: the optimal normal is near an axis,
# where doubles resolve tiny angles), or the whole pair rotated by a generic rotation (the
# optimal normal is generic: no rounded unit normal attains the value to 1e-9). Python floats
# only (the pairs are the doubles written, whatever the rounding of the construction).
import json, math
A0 = [[0.0,0.0,0.0],[8.0,0.0,0.0],[0.0,8.0,0.0],[0.0,0.0,-8.0]]   # face z=0 on top
def B0(d): return [[1.0,1.0,-d],[5.0,1.0,-d],[1.0,5.0,-d],[2.0,2.0,7.0]]
def rot_z_small(P, c, axis, th):
    # small rotation about an axis in the plane z = 0 through c: keep precision of tiny z
    ux,uy,uz = axis
    x,y,z = P[0]-c[0],P[1]-c[1],P[2]
    # only z changes by (axis x v).z * th = (ux*y - uy*x)*th ; x,y change by O(th*z) (~1e-24): ignore except apex
    nx = x + (uy*z)*th
    ny = y - (ux*z)*th
    nz = z + (ux*y - uy*x)*th
    return [c[0]+nx, c[1]+ny, nz]
def Rmat(axis, th):
    ux,uy,uz = axis; n=math.sqrt(ux*ux+uy*uy+uz*uz); ux,uy,uz=ux/n,uy/n,uz/n
    c,s=math.cos(th),math.sin(th); C=1-c
    return [[c+ux*ux*C, ux*uy*C-uz*s, ux*uz*C+uy*s],[uy*ux*C+uz*s, c+uy*uy*C, uy*uz*C-ux*s],[uz*ux*C-uy*s, uz*uy*C+ux*s, c+uz*uz*C]]
def apply(R, P, t=(0,0,0)): return [sum(R[i][k]*P[k] for k in range(3))+t[i] for i in range(3)]
pairs=[]
def add(name, A, B, tags): pairs.append({"name":name,"tags":["near-coplanar"]+tags,"A":A,"B":B})
cB = [7/3, 7/3, 0.0]
add("nc-flat-1e-12", A0, B0(1e-12), ["coordinate-plane"])
add("nc-flat-1e-11", A0, B0(1e-11), ["coordinate-plane"])
add("nc-rotx-1e-12", A0, [rot_z_small(p, cB, (1,0,0), 1e-12) for p in B0(1e-12)], ["coordinate-plane","rotated"])
add("nc-roty-1e-12", A0, [rot_z_small(p, cB, (0,1,0), 1e-12) for p in B0(1e-12)], ["coordinate-plane","rotated"])
s2 = math.sqrt(0.5)
add("nc-rotxy-1e-12", A0, [rot_z_small(p, cB, (s2,s2,0), 1e-12) for p in B0(1e-12)], ["coordinate-plane","rotated"])
add("nc-rotx-neg-1e-12", A0, [rot_z_small(p, cB, (1,0,0), -1e-12) for p in B0(1e-12)], ["coordinate-plane","rotated"])
add("nc-rot-3e-12-depth-2e-12", A0, [rot_z_small(p, cB, (0.6,0.8,0), 3e-12) for p in B0(2e-12)], ["coordinate-plane","rotated"])
# B larger than A's face region (B's face overhangs A's face): A small face
A1 = [[0.0,0.0,0.0],[6.0,0.0,0.0],[0.0,6.0,0.0],[2.0,2.0,-8.0]]
B1 = [[-1.0,-1.0,-1e-12],[8.0,-1.0,-1e-12],[-1.0,8.0,-1e-12],[1.0,1.0,6.0]]
add("nc-overhang-rotx-1e-12", A1, [rot_z_small(p, [2.0,2.0,0.0], (1,0,0), 1e-12) for p in B1], ["coordinate-plane","rotated"])
# not along a coordinate plane: the whole configuration rotated
R = Rmat((1,2,3), 0.7)
for nm, B in [("nc-generic-flat-1e-12", B0(1e-12)), ("nc-generic-rotx-1e-12", [rot_z_small(p, cB, (1,0,0), 1e-12) for p in B0(1e-12)])]:
    add(nm, [apply(R,p) for p in A0], [apply(R,p) for p in B], ["generic-plane"] + (["rotated"] if "rot" in nm else []))
# the y = 0 plane: A's face in y = 0, B rotated about z
A2 = [[0.0,0.0,0.0],[8.0,0.0,0.0],[0.0,0.0,8.0],[0.0,-8.0,0.0]]
B2 = [[1.0,-1e-12,1.0],[5.0,-1e-12,1.0],[1.0,-1e-12,5.0],[2.0,7.0,2.0]]
def rot_y0(P, c, th):  # rotate about the z-parallel line through c, small angle: y += th*(x - cx)
    return [P[0] - th*P[1], P[1] + th*(P[0]-c[0]), P[2]]
add("nc-yplane-rotz-1e-12", A2, [rot_y0(p, [7/3,0,7/3], 1e-12) for p in B2], ["coordinate-plane","rotated"])
# extra: deeper and shallower, and a generic orientation with a tilt about another axis
extra=[]
def addx(name, A, B, tags): extra.append({"name":name,"tags":["near-coplanar"]+tags,"A":A,"B":B})
addx("nc-flat-1e-15", A0, B0(1e-15), ["coordinate-plane"])
addx("nc-roty-1e-14", A0, [rot_z_small(p, cB, (0,1,0), 1e-14) for p in B0(1e-14)], ["coordinate-plane","rotated"])
R2 = Rmat((-2,1,5), 2.1)
addx("nc-generic2-rotxy-1e-12", [apply(R2,p) for p in A0], [apply(R2,p) for p in [rot_z_small(q, cB, (s2,s2,0), 1e-12) for q in B0(1e-12)]], ["generic-plane","rotated"])
addx("nc-generic2-flat-1e-13", [apply(R2,p) for p in A0], [apply(R2,p) for p in B0(1e-13)], ["generic-plane"])
pairs += extra
def fmt(p):
    return '  {"name": %s, "tags": %s,\n   "A": %s,\n   "B": %s}' % (json.dumps(p['name']), json.dumps(p['tags']), json.dumps(p['A']), json.dumps(p['B']))
import os, sys
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "near-coplanar.json")
open(out, "w").write('{"pairs": [\n' + ',\n'.join(fmt(p) for p in pairs) + '\n]}\n')
