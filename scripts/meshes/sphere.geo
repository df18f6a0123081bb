// A ball of radius R centred at (cx, cy, cz); mesh size h. scripts/make-meshes.sh sets the
// parameters with -setnumber.
SetFactory("OpenCASCADE");
DefineConstant[ cx = 0, cy = 0, cz = 0, R = 1, h = 0.3 ];
Sphere(1) = {cx, cy, cz, R};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
