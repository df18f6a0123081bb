// write_mesh.cpp — a tetrahedral mesh at new vertex positions as Gmsh 4.1 ASCII (.msh) or
// legacy VTK ASCII (.vtk) (pdd/mesh/write_mesh.h).
//
// Input : m (connectivity: its tetrahedra, in order), positions (one per vertex of m).
// Output: the file, written whole or not at all (atomic_file.h). Vertex i is Gmsh node tag
//         i + 1 (VTK point i), tetrahedron k Gmsh element tag k + 1 (VTK cell k), with m's
//         four vertex indices in m's order, so read_mesh gives back m's tetrahedra and these
//         positions: every coordinate is printed by std::to_chars in the shortest decimal that
//         reads back (strtod, correctly rounded) as the same double. Every vertex is written,
//         also those no tetrahedron uses, so vertex numbers are kept.
// Gmsh: one volume entity (tag 1) holding every node and every tetrahedron (element type 4),
// as Gmsh itself writes a discrete volume; no physical groups. VTK: version 3.0 (what
// ParaView, meshio and read_mesh read), POINTS double, CELLS, CELL_TYPES 10, no data.
// A non-finite coordinate is written as "nan" / "inf" (read back as such by read_mesh; Gmsh,
// VTK and meshio may reject it): positions from resolve() are finite wherever the input was.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <system_error>

#include "atomic_file.h"
#include "pdd/mesh.h"

namespace pdd::mesh {
namespace {

void put(std::string& out, double x) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);  // shortest round trip
  out.append(buf, ec == std::errc() ? end : buf);
}

void put(std::string& out, std::size_t n) {
  char buf[24];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, n);
  out.append(buf, ec == std::errc() ? end : buf);
}

void put_point(std::string& out, const Vec3d& p) {
  put(out, p[0]);
  out += ' ';
  put(out, p[1]);
  out += ' ';
  put(out, p[2]);
}

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string gmsh41(const Mesh& m, const std::vector<Vec3d>& p) {
  const std::size_t n = p.size(), t = m.tets.size();
  std::string out;
  out.reserve(64 + n * 60 + t * 40);
  out += "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  // The volume entity's bounding box, over the finite coordinates (0 when there are none).
  Vec3d lo{0, 0, 0}, hi{0, 0, 0};
  bool any = false;
  for (const Vec3d& q : p) {
    if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) continue;
    for (int k = 0; k < 3; ++k) {
      lo[k] = any ? std::min(lo[k], q[k]) : q[k];
      hi[k] = any ? std::max(hi[k], q[k]) : q[k];
    }
    any = true;
  }
  // numPoints numCurves numSurfaces numVolumes; volume: tag, box, 0 physical tags, 0 surfaces
  out += "$Entities\n0 0 0 1\n1 ";
  put_point(out, lo);
  out += ' ';
  put_point(out, hi);
  out += " 0 0\n$EndEntities\n";
  // numEntityBlocks numNodes minNodeTag maxNodeTag; block: entityDim entityTag parametric count
  out += "$Nodes\n";
  if (n == 0) {
    out += "0 0 0 0\n";
  } else {
    out += "1 ";
    put(out, n);
    out += " 1 ";
    put(out, n);
    out += "\n3 1 0 ";
    put(out, n);
    out += '\n';
    for (std::size_t i = 1; i <= n; ++i) put(out, i), out += '\n';
    for (const Vec3d& q : p) put_point(out, q), out += '\n';
  }
  out += "$EndNodes\n$Elements\n";
  // numEntityBlocks numElements minElementTag maxElementTag; block: dim tag type count
  if (t == 0) {
    out += "0 0 0 0\n";
  } else {
    out += "1 ";
    put(out, t);
    out += " 1 ";
    put(out, t);
    out += "\n3 1 4 ";
    put(out, t);
    out += '\n';
    for (std::size_t k = 0; k < t; ++k) {
      put(out, k + 1);
      for (std::size_t v : m.tets[k]) out += ' ', put(out, v + 1);
      out += '\n';
    }
  }
  out += "$EndElements\n";
  return out;
}

std::string vtk_legacy(const Mesh& m, const std::vector<Vec3d>& p) {
  const std::size_t n = p.size(), t = m.tets.size();
  std::string out;
  out.reserve(128 + n * 60 + t * 40);
  out += "# vtk DataFile Version 3.0\npdd: tetrahedral mesh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ";
  put(out, n);
  out += " double\n";
  for (const Vec3d& q : p) put_point(out, q), out += '\n';
  out += "CELLS ";
  put(out, t);
  out += ' ';
  put(out, 5 * t);
  out += '\n';
  for (const auto& tet : m.tets) {
    out += '4';
    for (std::size_t v : tet) out += ' ', put(out, v);
    out += '\n';
  }
  out += "CELL_TYPES ";
  put(out, t);
  out += '\n';
  for (std::size_t k = 0; k < t; ++k) out += "10\n";
  return out;
}

}  // namespace

void write_mesh(const std::string& path, const Mesh& m, const std::vector<Vec3d>& positions) {
  const std::string ext = lower_extension(path);
  if (ext != ".msh" && ext != ".vtk")
    throw std::runtime_error("cannot write mesh '" + path + "': unknown extension" +
                             (ext.empty() ? std::string() : " '" + ext + "'") +
                             " (.msh writes Gmsh 4.1 ASCII, .vtk legacy VTK ASCII)");
  if (positions.size() != m.vertices.size())
    throw std::invalid_argument("write_mesh '" + path + "': " + std::to_string(positions.size()) +
                                " positions for a mesh of " + std::to_string(m.vertices.size()) +
                                " vertices");
  for (std::size_t k = 0; k < m.tets.size(); ++k)
    for (std::size_t v : m.tets[k])
      if (v >= positions.size())
        throw std::invalid_argument("write_mesh '" + path + "': element " + std::to_string(k) +
                                    " refers to vertex " + std::to_string(v) + ", but the mesh has " +
                                    std::to_string(positions.size()) + " vertices");
  detail::write_whole_file(path, ext == ".msh" ? gmsh41(m, positions) : vtk_legacy(m, positions));
}

}  // namespace pdd::mesh
