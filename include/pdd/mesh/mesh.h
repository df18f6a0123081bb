// mesh/mesh.h — a tetrahedral mesh, reading it from a file, and what every mesh call shares:
// the elements it cannot compute (SkippedElement) and cancellation (Cancelled).
//
//   #include <pdd/mesh.h>             // CMake: target_link_libraries(app PRIVATE pdd::mesh)
//   pdd::mesh::Mesh A = pdd::mesh::read_mesh("a.msh");
//
// Inputs   a Gmsh .msh or legacy VTK .vtk file (read_mesh), or vertices and tetrahedra built in
//          code (Mesh).
// Outputs  Mesh: vertices (doubles) and tetrahedra (four vertex indices each, any orientation).
//
// Tetrahedra are numbered 0, 1, ... in file order among the file's tetrahedral elements; other
// element types (points, lines, triangles, hexahedra, ...) are ignored.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/pdd.h"

namespace pdd::mesh {

struct Mesh {
  std::vector<Vec3d> vertices;
  std::vector<std::array<std::size_t, 4>> tets;  // vertex indices into `vertices`
  // Where each tetrahedron came from, for messages: the element tag of a Gmsh file, the cell
  // index of a VTK file (same length as `tets`; may be empty for meshes built in code).
  std::vector<long long> source_ids;
  // Where each vertex with a non-finite coordinate came from, by vertex index, for the message
  // that skips its elements (element_problem): "node 5 at a.msh:12" (a Gmsh file's own node
  // tag and line), "point 4 at b.vtk:30" (a VTK file's point number), "VA[4]" (Python's array
  // and row). Empty for meshes built in code (the message then names the vertex index alone).
  std::map<std::size_t, std::string> vertex_sources;
};

// A mesh file that cannot be read: missing, truncated, malformed, an element referring to a
// node that is not in the file, an unknown element type. what() names the file and the line
// (text) or the byte offset (binary data): "a.msh:42: element 17 refers to node 999, which
// is not in the file".
struct ReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads a Gmsh .msh file (versions 2.2 and 4.1, ASCII and binary) or a legacy VTK unstructured
// grid (.vtk, ASCII or BINARY, cell type 10), chosen by content ("$MeshFormat" or
// "# vtk DataFile"). Coordinates are read as written (non-finite ones too: the element that
// uses them is skipped by contacts(), with its index and the vertex's node tag, file and line
// from vertex_sources). Throws ReadError.
Mesh read_mesh(const std::string& path);

// An element that was not computed (definitions §10): `mesh` is 'A' or 'B', `index` its number.
struct SkippedElement {
  char mesh = 'A';
  std::size_t index = 0;
  std::string reason;  // "element 12 of mesh A is flat: its four vertices are coplanar (volume 0)"
};

// What contacts(), resolve() and contact_energy() throw when their options' `cancel` flag
// stopped them.
struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("pdd::mesh: cancelled") {}
};

// Building blocks, for tests and benchmarks.
TetVertices element(const Mesh& m, std::size_t i);  // the vertices of tetrahedron i
// Why element i cannot be computed (non-finite coordinate, flat: exact), or nullopt.
std::optional<std::string> element_problem(const Mesh& m, std::size_t i, char which);

}  // namespace pdd::mesh
