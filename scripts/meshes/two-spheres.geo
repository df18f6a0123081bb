// Two overlapping balls in one mesh, meshed independently (no Boolean operation): a mesh
// that intersects itself, for self-contact (`pdd mesh --self`).
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.35 ];
Sphere(1) = {0, 0, 0, 1};
Sphere(2) = {1.3, 0.2, 0.1, 0.8};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
