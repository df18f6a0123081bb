// mesh/vtk.h — files for ParaView: the contacts of two meshes (write_vtk) and a resolution
// (write_resolution_vtk), each as one legacy VTK unstructured grid (ASCII) holding both meshes.
//
// Inputs   the meshes (or one: self-contact), the Contacts or the Resolution's positions and
//          report to show.
// Outputs  the file: points of A then of B, cells of A then of B, with the fields below.
#pragma once

#include <string>
#include <vector>

#include "pdd/mesh/contacts.h"
#include "pdd/mesh/mesh.h"
#include "pdd/mesh/resolve.h"
#include "pdd/pdd.h"

namespace pdd::mesh {

// Writes A and B (write_vtk_self: A alone, its self-contacts) as one legacy VTK unstructured grid (ASCII) for
// ParaView: points of A then of B, cells of A then of B, with cell data `mesh` (0 A, 1 B),
// `element` (its number in its mesh), `partners` (number of intersecting pairs it is in),
// `skipped` (1: the element was skipped, flat or with a non-finite vertex) and `max_<value>`
// (largest value of each requested variant over its pairs, 0 if none; `max_pdd2_global` for
// kGlobal); point data `non_finite` (1: a vertex with a non-finite coordinate, written at the
// origin since VTK readers reject nan) and, when kPdd2 was requested, `displacement`: for each mesh vertex, among the
// displacements q1 − rest that the pairs' pdd2 solutions give that vertex, the one of largest
// length (first in (a, b) order among equals); 0 where no pair moves it. Throws
// std::runtime_error when the file cannot be written.
template <class R>
void write_vtk(const std::string& path, const Mesh& A, const Mesh& B, const Contacts<R>& contacts,
               unsigned variants);
template <class R>
void write_vtk_self(const std::string& path, const Mesh& A, const Contacts<R>& contacts, unsigned variants);

// Writes a resolution for ParaView: A at positions a1 and B at b1 (write_resolution_vtk_self: A
// alone, self-contact)
// as one legacy VTK ASCII file, points of A then of B, cells of A then of B, with point data
// `displacement` (p1 - p0) and cell data `mesh` (0 A, 1 B), `element` (its number in its mesh),
// `volume_ratio` (V1 / V0, signed; doubles, for display), `shape_ratio` (eta1 / eta0 from
// the report; 0 where it has none), `remaining` (how many of report.remaining_pairs it is
// in), `bad` (1: in report.bad_elements) and `poor` (1: in report.poor_elements). A vertex with a
// non-finite coordinate is written at the origin (VTK readers reject nan). Written whole or
// not at all, as write_mesh; throws std::runtime_error when the file cannot be written.
void write_resolution_vtk(const std::string& path, const Mesh& A, const std::vector<Vec3d>& a1,
                          const Mesh& B, const std::vector<Vec3d>& b1, const ResolveReport& report);
void write_resolution_vtk_self(const std::string& path, const Mesh& A, const std::vector<Vec3d>& a1,
                               const ResolveReport& report);

}  // namespace pdd::mesh
