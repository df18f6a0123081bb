// A torus around the z axis (ring radius R, tube radius r); mesh size h.
SetFactory("OpenCASCADE");
DefineConstant[ R = 1, r = 0.25, h = 0.15 ];
Torus(1) = {0, 0, 0, R, r};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
