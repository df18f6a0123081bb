// mesh.h — pdd on tetrahedral meshes (definitions §10–§12): every header of pdd::mesh, one
// concept each, under pdd/mesh/. Include this one (or any of them alone).
//
//   #include <pdd/mesh.h>             // CMake: target_link_libraries(app PRIVATE pdd::mesh)
//   pdd::mesh::Mesh A = pdd::mesh::read_mesh("a.msh"), B = pdd::mesh::read_mesh("b.vtk");
//   pdd::mesh::Contacts<double> c = pdd::mesh::contacts(A, B);     // default variants
//   for (const auto& k : c.pairs) k.a, k.b, k.result.pdd2, k.result.q1_B ...;
//   pdd::mesh::Resolution r = pdd::mesh::resolve(A, B);             // no pair intersects
//   pdd::mesh::ContactEnergy e = pdd::mesh::contact_energy(A, B, r.a, r.b);
//
// Self-contact, one convention for every call: a function of two meshes f(A, B, ...) has a twin
// f_self(A, ...) for the self-contact of A (the element pairs a < b of A that share no vertex
// index; definitions §10, §11): contacts_self, contacts_exact_self, box_pairs_self,
// resolve_self, check_resolution_self, write_vtk_self, write_resolution_vtk_self,
// contact_energy_self. No function takes a nullable mesh. (Python: VB=None, TB=None.)
//
//   pdd/mesh/mesh.h              Mesh, read_mesh, ReadError; SkippedElement, Cancelled (shared
//                                by every call); element, element_problem
//   pdd/mesh/variants.h          which values contacts() computes: Variant bits, their names
//   pdd/mesh/contacts.h          contacts: every intersecting element pair and its depths
//   pdd/mesh/broadphase.h        box_pairs: stage 2 of contacts alone (for tests, benchmarks)
//   pdd/mesh/resolve.h           resolve: positions after which no element pair intersects
//   pdd/mesh/check_resolution.h  check_resolution: the exact verdict R1-R4 on given positions
//   pdd/mesh/write_mesh.h        write_mesh: a mesh with new positions, as .msh or .vtk
//   pdd/mesh/vtk.h               write_vtk, write_resolution_vtk: files for ParaView
//   pdd/mesh/contact_energy.h    contact_energy: E, its gradient and Hessian (definitions §12)
#pragma once

#include "pdd/mesh/mesh.h"
#include "pdd/mesh/variants.h"
#include "pdd/mesh/contacts.h"
#include "pdd/mesh/broadphase.h"
#include "pdd/mesh/resolve.h"
#include "pdd/mesh/check_resolution.h"
#include "pdd/mesh/write_mesh.h"
#include "pdd/mesh/vtk.h"
#include "pdd/mesh/contact_energy.h"
