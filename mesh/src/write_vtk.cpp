// write_vtk.cpp — both meshes and their contacts (write_vtk), or a resolution's new positions
// (write_resolution_vtk), in one legacy VTK file for ParaView (pdd/mesh/vtk.h).
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "atomic_file.h"
#include "element_quality.h"
#include "pdd/mesh.h"

namespace pdd::mesh {
namespace {

double to_double(double x) { return x; }
double to_double(const Rational& x) { return x.get_d(); }

// The cells of A then of B (B's point indices shifted by A's point count na), their types
// (10: tetrahedron) and the first two cell fields: `mesh` (0 A, 1 B) and `element` (its number
// in its mesh). Shared by both writers below.
void write_cells(std::ostream& out, const Mesh& A, const Mesh* B, std::size_t na) {
  const std::size_t ta = A.tets.size(), tb = B ? B->tets.size() : 0;
  out << "CELLS " << ta + tb << ' ' << 5 * (ta + tb) << '\n';
  for (const auto& t : A.tets) out << "4 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  if (B)
    for (const auto& t : B->tets)
      out << "4 " << na + t[0] << ' ' << na + t[1] << ' ' << na + t[2] << ' ' << na + t[3] << '\n';
  out << "CELL_TYPES " << ta + tb << '\n';
  for (std::size_t i = 0; i < ta + tb; ++i) out << "10\n";
  out << "CELL_DATA " << ta + tb << "\nSCALARS mesh int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < ta + tb; ++i) out << (i < ta ? 0 : 1) << '\n';
  out << "SCALARS element int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < ta + tb; ++i) out << (i < ta ? i : i - ta) << '\n';
}

}  // namespace

// write_vtk and write_vtk_self (B == nullptr).
template <class R>
static void contacts_vtk(const std::string& path, const Mesh& A, const Mesh* B, const Contacts<R>& contacts,
                         unsigned variants) {
  const std::size_t na = A.vertices.size(), nb = B ? B->vertices.size() : 0;
  const std::size_t ta = A.tets.size(), tb = B ? B->tets.size() : 0;
  // Cell data.
  std::vector<int> partners(ta + tb, 0);
  std::vector<std::array<double, kVariantCount>> maxima(ta + tb);
  for (auto& m : maxima) m.fill(0);
  // Point data: the longest displacement any pair's pdd2 solution gives the vertex.
  std::vector<Vec3d> disp(na + nb, Vec3d{0, 0, 0});
  std::vector<double> disp_len2(na + nb, 0);
  const std::size_t b_cell0 = B ? ta : 0, b_point0 = B ? na : 0;
  const Mesh& BB = B ? *B : A;
  for (const Contact<R>& c : contacts.pairs) {
    if (c.result.error) continue;
    const std::size_t cells[2] = {c.a, b_cell0 + c.b};
    for (std::size_t cell : cells) {
      ++partners[cell];
      for (std::size_t k = 0; k < kVariantCount; ++k)
        if (variants & (1u << k))
          maxima[cell][k] = std::max(maxima[cell][k], to_double(variant_value(c.result, k)));
    }
    if (!(variants & kPdd2)) continue;
    auto propose = [&](const Mesh& m, std::size_t tet, std::size_t point0, const Positions<R>& q1) {
      for (int v = 0; v < 4; ++v) {
        const std::size_t p = m.tets[tet][v];
        Vec3d d;
        double l2 = 0;
        for (int k = 0; k < 3; ++k) {
          d[k] = to_double(q1[v][k]) - m.vertices[p][k];
          l2 += d[k] * d[k];
        }
        if (l2 > disp_len2[point0 + p]) disp_len2[point0 + p] = l2, disp[point0 + p] = d;
      }
    };
    propose(A, c.a, 0, c.result.q1_A);
    propose(BB, c.b, b_point0, c.result.q1_B);
  }

  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out)
    throw std::runtime_error("cannot open '" + path + "' for writing" +
                             (errno ? std::string(": ") + std::strerror(errno) : ""));
  out.precision(17);
  out << "# vtk DataFile Version 3.0\n"
      << (B ? "pdd mesh: meshes A and B and their intersecting element pairs\n"
            : "pdd mesh --self: mesh A and its self-intersecting element pairs\n")
      << "ASCII\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << na + nb << " double\n";
  // VTK readers reject nan and inf: such a vertex is written at the origin and marked by the
  // point field `non_finite`, its elements by the cell field `skipped`.
  std::vector<char> non_finite(na + nb, 0);
  auto write_point = [&](const Vec3d& p, std::size_t id) {
    non_finite[id] = !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
    if (non_finite[id]) out << "0 0 0\n";
    else out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  };
  for (std::size_t i = 0; i < na; ++i) write_point(A.vertices[i], i);
  if (B)
    for (std::size_t i = 0; i < nb; ++i) write_point(B->vertices[i], na + i);
  write_cells(out, A, B, na);
  out << "SCALARS partners int 1\nLOOKUP_TABLE default\n";
  for (int p : partners) out << p << '\n';
  // 1: the element was skipped (flat, or a vertex not finite; contacts' `skipped`), no values
  std::vector<char> skipped(ta + tb, 0);
  for (const SkippedElement& e : contacts.skipped) skipped[(e.mesh == 'B' ? b_cell0 : 0) + e.index] = 1;
  out << "SCALARS skipped int 1\nLOOKUP_TABLE default\n";
  for (char k : skipped) out << int(k) << '\n';
  for (std::size_t k = 0; k < kVariantCount; ++k) {
    if (!(variants & (1u << k))) continue;
    out << "SCALARS max_" << kVariantKeys[k] << " double 1\nLOOKUP_TABLE default\n";
    for (const auto& m : maxima) out << m[k] << '\n';
  }
  out << "POINT_DATA " << na + nb << "\nSCALARS non_finite int 1\nLOOKUP_TABLE default\n";
  for (char k : non_finite) out << int(k) << '\n';
  if (variants & kPdd2) {
    out << "VECTORS displacement double\n";
    for (const Vec3d& d : disp) out << d[0] << ' ' << d[1] << ' ' << d[2] << '\n';
  }
  out.flush();
  if (!out) throw std::runtime_error("cannot write to '" + path + "'" + (errno ? std::string(": ") + std::strerror(errno) : ""));
}

// write_resolution_vtk and write_resolution_vtk_self (B == nullptr).
static void resolution_vtk(const std::string& path, const Mesh& A, const std::vector<Vec3d>& a1,
                           const Mesh* B, const std::vector<Vec3d>& b1, const ResolveReport& report) {
  if (a1.size() != A.vertices.size() || (B && b1.size() != B->vertices.size()))
    throw std::invalid_argument("write_resolution_vtk '" + path +
                                "': not one new position per vertex");
  const std::size_t na = A.vertices.size(), nb = B ? B->vertices.size() : 0;
  const std::size_t ta = A.tets.size(), tb = B ? B->tets.size() : 0;
  std::ostringstream out;
  out.precision(17);
  out << "# vtk DataFile Version 3.0\n"
      << (B ? "pdd resolve: meshes A and B at their new positions\n"
            : "pdd resolve --self: mesh A at its new positions\n")
      << "ASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " << na + nb << " double\n";
  auto finite = [](const Vec3d& p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
  };
  auto point = [&](const Vec3d& p) {
    if (finite(p)) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    else out << "0 0 0\n";
  };
  for (const Vec3d& p : a1) point(p);
  if (B)
    for (const Vec3d& p : b1) point(p);
  write_cells(out, A, B, na);
  // V1 / V0 from the doubles (display only: report.bad_elements is the exact verdict), each
  // volume of the edges scaled by the rest element's power of two (element_quality.h's
  // edge_scale: the same ratio, in range at any mesh size).
  auto volume6 = [](const std::vector<Vec3d>& p, const std::array<std::size_t, 4>& t, double f) {
    double e[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) e[r][k] = (p[t[r + 1]][k] - p[t[0]][k]) * f;
    return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
           e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  };
  out << "SCALARS volume_ratio double 1\nLOOKUP_TABLE default\n";
  auto ratios = [&](const Mesh& m, const std::vector<Vec3d>& p1) {
    for (const auto& t : m.tets) {
      const TetVertices t0 = {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]};
      const double f = detail::edge_scale(t0), v0 = volume6(m.vertices, t, f), v1 = volume6(p1, t, f), r = v1 / v0;
      out << (std::isfinite(r) ? r : 0.0) << '\n';
    }
  };
  ratios(A, a1);
  if (B) ratios(*B, b1);
  // eta1 / eta0 from the report (doubles, display only: report.poor_elements is the verdict);
  // 0 where the report has none (an element skipped or non-finite).
  out << "SCALARS shape_ratio double 1\nLOOKUP_TABLE default\n";
  auto shapes = [&](const std::vector<double>& r, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) out << (i < r.size() && std::isfinite(r[i]) ? r[i] : 0.0) << '\n';
  };
  shapes(report.shape_ratio_a, ta);
  if (B) shapes(report.shape_ratio_b, tb);
  std::vector<int> remaining(ta + tb, 0), bad(ta + tb, 0), poor(ta + tb, 0);
  const std::size_t b_cell0 = B ? ta : 0;
  for (const auto& [a, b] : report.remaining_pairs) {
    if (a < ta) ++remaining[a];
    if (b_cell0 + b < ta + tb) ++remaining[b_cell0 + b];
  }
  for (const auto& [which, i] : report.bad_elements) {
    const std::size_t cell = (which == 'B' ? b_cell0 : 0) + i;
    if (cell < ta + tb) bad[cell] = 1;
  }
  for (const auto& [which, i] : report.poor_elements) {
    const std::size_t cell = (which == 'B' ? b_cell0 : 0) + i;
    if (cell < ta + tb) poor[cell] = 1;
  }
  out << "SCALARS remaining int 1\nLOOKUP_TABLE default\n";
  for (int k : remaining) out << k << '\n';
  out << "SCALARS bad int 1\nLOOKUP_TABLE default\n";
  for (int k : bad) out << k << '\n';
  out << "SCALARS poor int 1\nLOOKUP_TABLE default\n";
  for (int k : poor) out << k << '\n';
  out << "POINT_DATA " << na + nb << "\nVECTORS displacement double\n";
  auto displacement = [&](const Vec3d& p0, const Vec3d& p1) {
    if (finite(p0) && finite(p1)) out << p1[0] - p0[0] << ' ' << p1[1] - p0[1] << ' ' << p1[2] - p0[2] << '\n';
    else out << "0 0 0\n";
  };
  for (std::size_t i = 0; i < na; ++i) displacement(A.vertices[i], a1[i]);
  if (B)
    for (std::size_t i = 0; i < nb; ++i) displacement(B->vertices[i], b1[i]);
  detail::write_whole_file(path, out.str());
}

template <class R>
void write_vtk(const std::string& path, const Mesh& A, const Mesh& B, const Contacts<R>& contacts,
               unsigned variants) {
  contacts_vtk(path, A, &B, contacts, variants);
}
template <class R>
void write_vtk_self(const std::string& path, const Mesh& A, const Contacts<R>& contacts, unsigned variants) {
  contacts_vtk(path, A, nullptr, contacts, variants);
}
void write_resolution_vtk(const std::string& path, const Mesh& A, const std::vector<Vec3d>& a1,
                          const Mesh& B, const std::vector<Vec3d>& b1, const ResolveReport& report) {
  resolution_vtk(path, A, a1, &B, b1, report);
}
void write_resolution_vtk_self(const std::string& path, const Mesh& A, const std::vector<Vec3d>& a1,
                               const ResolveReport& report) {
  resolution_vtk(path, A, a1, nullptr, {}, report);
}

template void write_vtk<double>(const std::string&, const Mesh&, const Mesh&, const Contacts<double>&, unsigned);
template void write_vtk<Rational>(const std::string&, const Mesh&, const Mesh&, const Contacts<Rational>&, unsigned);
template void write_vtk_self<double>(const std::string&, const Mesh&, const Contacts<double>&, unsigned);
template void write_vtk_self<Rational>(const std::string&, const Mesh&, const Contacts<Rational>&, unsigned);

}  // namespace pdd::mesh
