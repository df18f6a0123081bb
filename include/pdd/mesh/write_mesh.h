// mesh/write_mesh.h — a mesh with new vertex positions, written as a Gmsh or VTK file that reads
// back bit for bit (the output of `pdd resolve`).
//
// Inputs   the path (its extension chooses the format), the mesh (its tetrahedra), the positions.
// Outputs  the file, whole or not at all.
#pragma once

#include <string>
#include <vector>

#include "pdd/mesh/mesh.h"
#include "pdd/pdd.h"

namespace pdd::mesh {

// Writes m with its vertices replaced by `positions` (same count) as Gmsh 4.1 ASCII (.msh) or
// legacy VTK ASCII (.vtk), chosen by the path's extension, tetrahedra in m's order, every
// coordinate printed so that it reads back as the same double. Throws std::runtime_error when
// the extension is neither or the file cannot be written (nothing partial is left: a new or
// regular file is written under a temporary name beside it and renamed; a device is written
// in place), std::invalid_argument when `positions` does not have one entry per vertex.
void write_mesh(const std::string& path, const Mesh& m, const std::vector<Vec3d>& positions);

}  // namespace pdd::mesh
