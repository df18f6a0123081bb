// An axis-aligned box [x0, x0+dx] x [y0, y0+dy] x [z0, z0+dz]; mesh size h.
SetFactory("OpenCASCADE");
DefineConstant[ x0 = 0, y0 = 0, z0 = 0, dx = 1, dy = 1, dz = 1, h = 0.3 ];
Box(1) = {x0, y0, z0, dx, dy, dz};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
