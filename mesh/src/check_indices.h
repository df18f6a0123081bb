// check_indices.h — the one check every mesh entry point makes first: every tetrahedron's four
// vertex indices lie inside the mesh's vertex list (contacts(), resolve(), check_resolution()).
//
// Inputs:  m      the mesh;  which  'A' or 'B', the mesh's name in the message
// Throws:  std::invalid_argument "element i of mesh A refers to vertex v, but the mesh has n
//          vertices" for the first index out of range.
#pragma once

#include "pdd/mesh.h"

namespace pdd::mesh::detail {

void check_indices(const Mesh& m, char which);

}  // namespace pdd::mesh::detail
