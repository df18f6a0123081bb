// A ball inside a box, meshed together (BooleanFragments) so that the sphere between them has
// one triangulation: a conforming, curved interface. Only the tetrahedra of `part` are saved
// (1: the ball, 2: the box around it); the physical group selects them (without physical
// groups Gmsh saves everything). Physical groups do not change the mesh, so the runs for part
// 1 and part 2 mesh the same geometry identically and the interface triangles match.
SetFactory("OpenCASCADE");
DefineConstant[ part = 1, h = 0.3 ];
Box(1) = {-1, -1, -1, 2, 2, 2};
Sphere(2) = {0, 0, 0, 0.7};
v() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; };
// v(0) is the ball (the tool, kept as is), v(1) the box minus the ball.
Physical Volume(1) = {v(part - 1)};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
