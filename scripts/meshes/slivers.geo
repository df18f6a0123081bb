// A box meshed by plain Delaunay with every quality optimisation off: the tetrahedra the
// Delaunay kernel leaves behind include slivers (four nearly coplanar vertices, dihedral
// angles near 0 and 180 degrees), which later passes would normally remove.
SetFactory("OpenCASCADE");
DefineConstant[ x0 = 0, y0 = 0, z0 = 0, dx = 1, dy = 1, dz = 1, h = 0.3 ];
Box(1) = {x0, y0, z0, dx, dy, dz};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.Algorithm3D = 1;   // Delaunay
Mesh.Optimize = 0;      // no sliver removal
Mesh.OptimizeNetgen = 0;
