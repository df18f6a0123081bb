// tests/mesh — pdd::mesh (include/pdd/mesh.h, definitions §10) on the meshes Gmsh wrote
// (fixtures/meshes/, scripts/make-meshes.sh):
//   readers: the same ball in MSH 2.2 / 4.1, ASCII / binary and legacy VTK ASCII / binary
//            reads to the same tetrahedra; bad files give messages naming the line or element;
//   pairs:   the pair set equals brute force over all N·M (self: all i < j sharing no vertex)
//            element pairs with the exact decision: nothing missed, nothing extra;
//   values:  each pair's record equals pdd::fast::solve_pair on that pair, for every variant
//            subset path, definitions §9's global keys included (and cleared when not requested);
//            the exact engine on a tiny mesh gives pdd::reference::solve_pair's exact record
//            and the fast values are within definitions §8 of it (pdd2_global: of the exact interval
//            [pdd2_global_lower, pdd2_global]);
//   touching meshes (a shared plane, a conforming curved interface) give no pair.
#define BOOST_TEST_MODULE mesh
#include <boost/test/unit_test.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "kuhn_grid_mesh.h"
#include "pdd/mesh.h"

using namespace pdd;
using namespace pdd::mesh;

namespace {

const std::string kDir = std::string(PDD_FIXTURES_DIR) + "/meshes/";
Mesh load(const std::string& name) { return read_mesh(kDir + name); }

using PairSet = std::vector<std::array<std::size_t, 2>>;

// Options computing the variants `v` (every other option at its default).
ContactOptions computing(unsigned v) {
  ContactOptions o;
  o.variants = v;
  return o;
}

// All N·M pairs (self: i < j sharing no vertex), exact decision, no boxes.
PairSet brute_force(const Mesh& A, const Mesh* B) {
  const Mesh& BB = B ? *B : A;
  std::vector<std::vector<std::size_t>> hits(A.tets.size());
  tbb::parallel_for(std::size_t{0}, A.tets.size(), [&](std::size_t i) {
    if (element_problem(A, i, 'A')) return;
    const TetVertices Ti = element(A, i);
    for (std::size_t j = B ? 0 : i + 1; j < BB.tets.size(); ++j) {
      if (element_problem(BB, j, 'B')) continue;
      if (!B) {
        bool share = false;
        for (auto u : A.tets[i])
          for (auto v : A.tets[j]) share |= u == v;
        if (share) continue;
      }
      const fast::Depth d = fast::rigid_pd2(Ti, element(BB, j));
      if (d.status != fast::DepthStatus::Ok || d.pd2 > 0) hits[i].push_back(j);  // status: fails the test
    }
  });
  PairSet out;
  for (std::size_t i = 0; i < hits.size(); ++i)
    for (std::size_t j : hits[i]) out.push_back({i, j});
  return out;
}

template <class R>
PairSet pairs_of(const Contacts<R>& c) {
  PairSet out;
  for (const auto& p : c.pairs) out.push_back({p.a, p.b});
  return out;
}

void check_pair_set(const std::string& a, const std::string& b) {
  const Mesh A = load(a), B = load(b);
  const Contacts<double> c = contacts(A, B, computing(kRigid));
  const PairSet expected = brute_force(A, &B);
  BOOST_TEST_MESSAGE(a << " x " << b << ": " << A.tets.size() << " x " << B.tets.size()
                       << " elements, " << c.box_pairs << " box pairs, " << expected.size()
                       << " intersecting");
  BOOST_TEST(!expected.empty());
  BOOST_TEST(c.skipped.empty());
  BOOST_TEST((pairs_of(c) == expected));
}

void check_values(const Contacts<double>& c, const Mesh& A, const Mesh& B, unsigned variants) {
  for (const auto& p : c.pairs) {
    const PairResult<double> r = fast::solve_pair(TetPair{"", {}, element(A, p.a), element(B, p.b)});
    BOOST_REQUIRE(!r.error);
    BOOST_REQUIRE(!p.result.error);
    BOOST_TEST(p.result.intersecting);
    for (std::size_t k = 0; k < kValueCount; ++k) {
      const bool on = variants & (1u << k);
      BOOST_TEST(record_value(p.result, k) == (on ? record_value(r, k) : 0.0), kValueKeys[k]);
      if (kLabelOfValue[k] >= 0) {
        const auto& got = record_label(p.result, kLabelOfValue[k]);
        const auto& want = record_label(r, kLabelOfValue[k]);
        BOOST_TEST((got ? got->str() : "-") == (on && want ? want->str() : "-"), kLabelKeys[kLabelOfValue[k]]);
      }
    }
    if (variants & kPdd2) BOOST_TEST((p.result.q1_A == r.q1_A && p.result.q1_B == r.q1_B));
    // definitions §9: solve_pair's fields bit for bit (mesh.h: the same call), below pdd2_relaxed
    // (definitions §9: a minimum over every normal, the candidates' included); else cleared.
    const TetVertices Ta = element(A, p.a), Tb = element(B, p.b);
    if (variants & kGlobal) {
      BOOST_TEST(p.result.pdd2_global > 0.0);
      BOOST_TEST(p.result.pdd2_global == r.pdd2_global);
      BOOST_TEST(p.result.pdd2_global <= r.pdd2_relaxed);
      BOOST_TEST((p.result.pdd2_global_normal && r.pdd2_global_normal &&
                  *p.result.pdd2_global_normal == *r.pdd2_global_normal));
      BOOST_TEST((p.result.q1_A_global == r.q1_A_global && p.result.q1_B_global == r.q1_B_global));
    } else {
      BOOST_TEST(p.result.pdd2_global == 0.0);
      BOOST_TEST(!p.result.pdd2_global_normal);
      BOOST_TEST((p.result.q1_A_global == Ta && p.result.q1_B_global == Tb));
    }
    BOOST_TEST(!p.result.pdd2_global_lower);
  }
}

// A tetrahedron's rest pose as exact rationals (each double taken exactly).
Positions<Rational> exact_pose(const TetVertices& T) {
  Positions<Rational> p;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = Rational(T[i][k]);
  return p;
}

std::string read_error(const std::string& name) {
  try {
    load(name);
  } catch (const ReadError& e) {
    return e.what();
  }
  return "(no error)";
}

bool contains(const std::string& s, const std::string& part) {
  if (s.find(part) != std::string::npos) return true;
  BOOST_TEST_MESSAGE("'" << s << "' lacks '" << part << "'");
  return false;
}

}  // namespace

// Gmsh writes ASCII coordinates with 16 significant digits, which does not round-trip every
// double, and binary ones exactly: the ASCII files agree with each other exactly, the binary
// ones too, and the two groups to within a unit in the 16th digit.
BOOST_AUTO_TEST_CASE(every_encoding_reads_the_same_tetrahedra) {
  const Mesh text = load("sphere-a.msh"), bin = load("sphere-a.bin41.msh");
  BOOST_TEST(text.tets.size() == 898u);  // Gmsh's count for this ball (triangles, lines ignored)
  auto same = [](const Mesh& x, const Mesh& y, double tol) {
    if (x.tets.size() != y.tets.size()) return false;
    for (std::size_t i = 0; i < x.tets.size(); ++i) {
      const TetVertices a = element(x, i), b = element(y, i);
      for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k)
          if (std::abs(a[v][k] - b[v][k]) > tol) return false;
    }
    return true;
  };
  for (const char* f : {"sphere-a.v22.msh", "sphere-a.vtk"})
    BOOST_TEST(same(load(f), text, 0.0), f);
  for (const char* f : {"sphere-a.bin22.msh", "sphere-a.bin.vtk"})
    BOOST_TEST(same(load(f), bin, 0.0), f);
  BOOST_TEST(same(text, bin, 1e-15));
  BOOST_TEST(!same(text, bin, 0.0));  // so the exact comparisons above mean something
}

BOOST_AUTO_TEST_CASE(bad_files_name_the_line_or_element) {
  BOOST_TEST(contains(read_error("bad/truncated.msh"), "truncated.msh:"));
  BOOST_TEST(contains(read_error("bad/truncated.msh"), "truncated?"));
  BOOST_TEST(contains(read_error("bad/truncated.bin41.msh"), "truncated?"));
  BOOST_TEST(contains(read_error("bad/truncated.bin41.msh"), ": byte "));
  BOOST_TEST(contains(read_error("bad/truncated.bin22.msh"), "truncated?"));
  BOOST_TEST(contains(read_error("bad/truncated.vtk"), "truncated?"));
  BOOST_TEST(contains(read_error("bad/missing-node.msh"),
                      "missing-node.msh:14: element 2 (tetrahedron 1) refers to node 7, which is not in the file"));
  BOOST_TEST(contains(read_error("bad/bad-number.msh"), "bad-number.msh:8: a node coordinate: '0.3x' is not a number"));
  BOOST_TEST(contains(read_error("bad/bad-index.vtk"), "bad-index.vtk:12: cell 1 (tetrahedron 1) refers to point 9"));
  BOOST_TEST(contains(read_error("bad/README.md"), "neither a Gmsh mesh"));
  BOOST_TEST(contains(read_error("does-not-exist.msh"), "cannot read"));
  // A NUL in a section name: the message shows it as \x00 instead of ending
  // there ("section $No").
  const std::string path = (std::filesystem::temp_directory_path() / "pdd-nul-section.msh").string();
  {
    std::ofstream f(path, std::ios::binary);
    f << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$No" << '\0' << "des\n1\n1 0 0 0\n$EndNodes\n";
  }
  std::string why = "(no error)";
  try {
    read_mesh(path);
  } catch (const ReadError& e) {
    why = e.what();
  }
  BOOST_TEST(contains(why, "nul-section.msh:4: section $No\\x00des has no $EndNo\\x00des"));
}

// A non-finite vertex is named by the file's own number (Gmsh node tag, VTK point number) and
// where it was read (line; byte offset in binary data), in every reader. Each file has one
// tetrahedron over four nodes, the third (mesh vertex 2) with a non-finite coordinate; the line
// and byte numbers below are counted from the text written.
std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}
std::string skip_reason(const std::string& path) {
  const Mesh m = read_mesh(path);
  BOOST_REQUIRE(m.tets.size() == 1u);
  BOOST_REQUIRE(m.vertex_sources.size() == 1u);
  const auto why = element_problem(m, 0, 'A');
  BOOST_REQUIRE(why);
  return *why;
}
template <class T>
std::string bytes(T v, bool big_endian) {
  std::string b(sizeof v, '\0');
  std::memcpy(b.data(), &v, sizeof v);
  if (big_endian) std::reverse(b.begin(), b.end());
  return b;
}

BOOST_AUTO_TEST_CASE(non_finite_vertex_named_by_file_line_and_node_tag) {
  {  // MSH 2.2 ASCII, tags 10..40 (not the vertex index + 1); node 30 on line 8
    const std::string p = write_file("pdd-nan-v22.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n10 0 0 0\n20 1 0 0\n30 0 nan 0\n40 0 0 1\n"
        "$EndNodes\n$Elements\n1\n7 4 2 0 1 10 20 30 40\n$EndElements\n");
    BOOST_TEST(skip_reason(p) == "element 0 of mesh A: vertex 2 (mesh vertex 2: node 30 at " + p +
                                     ":8) coordinate y is not finite (nan)");
  }
  {  // MSH 4.1 ASCII, two node blocks; node 7's coordinates on line 14 (its tag on line 12)
    const std::string p = write_file("pdd-nan-v41.msh",
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n2 4 5 8\n"
        "3 1 0 2\n5\n6\n0 0 0\n1 0 0\n"
        "3 1 0 2\n7\n8\n-inf 1 0\n0 0 1\n"
        "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 5 6 7 8\n$EndElements\n");
    BOOST_TEST(skip_reason(p) == "element 0 of mesh A: vertex 2 (mesh vertex 2: node 7 at " + p +
                                     ":14) coordinate x is not finite (-inf)");
  }
  {  // legacy VTK ASCII: point 2 on line 8
    const std::string p = write_file("pdd-nan.vtk",
        "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
        "0 0 0\n1 0 0\n0 1 inf\n0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n");
    BOOST_TEST(skip_reason(p) == "element 0 of mesh A: vertex 2 (mesh vertex 2: point 2 at " + p +
                                     ":8) coordinate z is not finite (inf)");
  }
  {  // legacy VTK BINARY (big-endian floats): point 2 starts 24 bytes into the point data
    const std::string head = "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n";
    std::string points;
    const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, std::nanf("")}, {0, 0, 1}};
    for (const auto& v : xyz)
      for (float c : v) points += bytes(c, true);
    std::string cells = "\nCELLS 1 5\n";
    for (std::int32_t v : {4, 0, 1, 2, 3}) cells += bytes(v, true);
    cells += "\nCELL_TYPES 1\n" + bytes(std::int32_t(10), true) + "\n";
    const std::string p = write_file("pdd-nan.bin.vtk", head + points + cells);
    BOOST_TEST(skip_reason(p) == "element 0 of mesh A: vertex 2 (mesh vertex 2: point 2 at " + p + ", byte " +
                                     std::to_string(head.size() + 24) + ") coordinate z is not finite (nan)");
  }
  {  // MSH 2.2 binary: node records of 4 + 3 * 8 bytes, node 30 the third
    const std::string head = "$MeshFormat\n2.2 1 8\n" + bytes(std::int32_t(1), false) + "\n$EndMeshFormat\n$Nodes\n4\n";
    std::string nodes;
    const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, std::nan("")}, {0, 0, 1}};
    for (int i = 0; i < 4; ++i) {
      nodes += bytes(std::int32_t(10 * (i + 1)), false);
      for (double c : xyz[i]) nodes += bytes(c, false);
    }
    std::string elements = "\n$EndNodes\n$Elements\n1\n";
    for (std::int32_t v : {4, 1, 0, 7, 10, 20, 30, 40}) elements += bytes(v, false);
    elements += "\n$EndElements\n";
    const std::string p = write_file("pdd-nan.bin22.msh", head + nodes + elements);
    BOOST_TEST(skip_reason(p) == "element 0 of mesh A: vertex 2 (mesh vertex 2: node 30 at " + p + ", byte " +
                                     std::to_string(head.size() + 2 * 28) + ") coordinate z is not finite (nan)");
  }
  {  // a mesh built in code names the vertex index alone
    const Mesh m{{{0, 0, 0}, {1, 0, 0}, {0, 1, NAN}, {0, 0, 1}}, {{0, 1, 2, 3}}, {}, {}};
    BOOST_TEST(*element_problem(m, 0, 'B') == "element 0 of mesh B: vertex 2 (mesh vertex 2) coordinate z is not finite (nan)");
  }
}

BOOST_AUTO_TEST_CASE(flat_and_nan_elements_are_reported_and_skipped) {
  const Mesh ball = load("sphere-a.msh");
  {
    const Mesh m = load("bad/flat.msh");
    BOOST_REQUIRE(m.tets.size() == 2u);  // the point element is ignored
    const Contacts<double> c = contacts(m, ball);
    BOOST_REQUIRE(c.skipped.size() == 1u);
    BOOST_TEST(c.skipped[0].mesh == 'A');
    BOOST_TEST(c.skipped[0].index == 1u);
    BOOST_TEST(contains(c.skipped[0].reason, "element 1 of mesh A is flat"));
    BOOST_TEST(!c.pairs.empty());  // the rest is computed: element 0 sits inside the ball
    for (const auto& p : c.pairs) BOOST_TEST(p.a == 0u);
  }
  {
    const Mesh m = load("bad/nan.msh");  // element 0 has the NaN node, element 1 is flat
    const Contacts<double> c = contacts(ball, m);
    BOOST_REQUIRE(c.skipped.size() == 2u);
    BOOST_TEST(c.skipped[0].mesh == 'B');
    BOOST_TEST(c.skipped[0].index == 0u);
    // nan.msh's node 4 (mesh vertex 3) is on line 9 of the file
    BOOST_TEST(c.skipped[0].reason == "element 0 of mesh B: vertex 3 (mesh vertex 3: node 4 at " + kDir +
                                          "bad/nan.msh:9) coordinate z is not finite (nan)");
    BOOST_TEST(c.skipped[1].index == 1u);
    BOOST_TEST(c.pairs.empty());
    // In the VTK file both skipped elements of B are marked (cells after the ball's) and the
    // NaN vertex (B's vertex 3) is marked non_finite where it is written at the origin.
    const std::string path = "mesh_test_skipped.vtk";
    write_vtk(path, ball, m, c, kDefaultVariants);
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto field = [&](const std::string& header, std::size_t count) {
      const std::size_t at = text.find(header + "\nLOOKUP_TABLE default\n");
      BOOST_REQUIRE(at != std::string::npos);
      std::istringstream values(text.substr(at + header.size() + 22));
      std::vector<int> out(count);
      for (int& v : out) values >> v;
      return out;
    };
    const std::vector<int> skipped = field("SCALARS skipped int 1", ball.tets.size() + m.tets.size());
    for (std::size_t i = 0; i < skipped.size(); ++i) BOOST_TEST(skipped[i] == (i >= ball.tets.size() ? 1 : 0), i);
    const std::vector<int> non_finite = field("SCALARS non_finite int 1", ball.vertices.size() + m.vertices.size());
    for (std::size_t i = 0; i < non_finite.size(); ++i)
      BOOST_TEST(non_finite[i] == (i == ball.vertices.size() + 3 ? 1 : 0), i);
  }
}

BOOST_AUTO_TEST_CASE(pair_set_equals_brute_force) {
  check_pair_set("sphere-a.msh", "sphere-b.msh");
  check_pair_set("torus.msh", "box.vtk");
  check_pair_set("slivers.msh", "sphere-a.bin22.msh");
}

BOOST_AUTO_TEST_CASE(self_contact_equals_brute_force) {
  const Mesh m = load("two-spheres.msh");
  const Contacts<double> c = contacts_self(m, computing(kRigid | kAccel1));
  const PairSet expected = brute_force(m, nullptr);
  BOOST_TEST(!expected.empty());
  BOOST_TEST((pairs_of(c) == expected));
  for (const auto& p : c.pairs) BOOST_TEST(p.a < p.b);
  // A valid conforming mesh does not intersect itself.
  BOOST_TEST(contacts_self(load("sphere-a.msh")).pairs.empty());
  BOOST_TEST(contacts_self(load("slivers.msh")).pairs.empty());
}

BOOST_AUTO_TEST_CASE(values_equal_solve_pair) {
  const Mesh A = load("slivers.msh"), B = load("sphere-a.msh");
  for (unsigned v : {kAllVariants, kDefaultVariants, unsigned(kRigid | kAccel1), unsigned(kStatic),
                     unsigned(kRelaxed | kAccel6), unsigned(kGlobal), unsigned(kRigid | kGlobal),
                     unsigned(kPdd2 | kGlobal)}) {
    BOOST_TEST_CONTEXT(variant_names(v)) {
      const Contacts<double> c = contacts(A, B, computing(v));
      BOOST_TEST(!c.pairs.empty());
      check_values(c, A, B, v);
    }
  }
  const Mesh S = load("two-spheres.msh");
  check_values(contacts_self(S, computing(kAllVariants)), S, S, kAllVariants);
}


// Grids of cell 2^-2 against copies shifted by half a cell (along (1, 1, 1), and along x), and
// one stacked a whole cell up a quarter deep: most element pairs repeat up to an exact
// translation, and contacts() computes each kind once (translation_memo.h). The pairs are the
// brute-force ones and every record is solve_pair's on its own pair, bit for bit: all the
// requested fields (check_values).
BOOST_AUTO_TEST_CASE(repeated_pairs_of_a_structured_mesh_equal_solve_pair) {
  using test::kuhn_grid;  // (tests/support/kuhn_grid_mesh.h)
  const Mesh A = kuhn_grid(5, 0.25, {0, 0, 0});
  for (const std::array<double, 3>& t : {std::array<double, 3>{0.125, 0.125, 0.125},
                                         std::array<double, 3>{0.125, 0, 0},
                                         std::array<double, 3>{0, 0, 1.0625}}) {
    const Mesh B = kuhn_grid(5, 0.25, t);
    BOOST_TEST_CONTEXT("shift " << t[0] << " " << t[1] << " " << t[2]) {
      const Contacts<double> c = contacts(A, B);
      BOOST_TEST((pairs_of(c) == brute_force(A, &B)));
      BOOST_TEST(c.pairs.size() > 100u);
      check_values(c, A, B, kDefaultVariants);
      for (unsigned v : {unsigned(kRigid | kAccel1), unsigned(kGlobal), kAllVariants})
        BOOST_TEST_CONTEXT(variant_names(v)) { check_values(contacts(A, B, computing(v)), A, B, v); }
    }
  }
  const Mesh S = kuhn_grid(4, 0.5, {0, 0, 0});
  Mesh two = S;  // self-contact: the grid and its copy a quarter cell along (1, 1, 1), one mesh
  const std::size_t nv = S.vertices.size();
  for (std::size_t v = 0; v < nv; ++v)
    two.vertices.push_back({S.vertices[v][0] + 0.125, S.vertices[v][1] + 0.125, S.vertices[v][2] + 0.125});
  for (auto t : S.tets) {
    for (auto& i : t) i += nv;
    two.tets.push_back(t);
  }
  const Contacts<double> self = contacts_self(two, computing(kAllVariants));
  BOOST_TEST((pairs_of(self) == brute_force(two, nullptr)));
  check_values(self, two, two, kAllVariants);
}

BOOST_AUTO_TEST_CASE(progress_starts_at_zero_and_cancel_stops_the_call) {
  const Mesh A = load("slivers.msh"), B = load("sphere-a.msh");
  const std::size_t total = contacts(A, B).pairs.size();
  BOOST_REQUIRE(total > 100u);
  // progress: (0, total) first, then every pair once
  std::atomic<std::size_t> calls{0}, done{0}, first_n{1}, first_total{0};
  ContactOptions o;
  o.progress = [&](std::size_t n, std::size_t t) {
    if (calls++ == 0) first_n = n, first_total = t;
    done += n;
  };
  contacts(A, B, o);
  BOOST_TEST(first_n == 0u);
  BOOST_TEST(first_total == total);
  BOOST_TEST(done == total);
  // cancelled before the call: nothing is computed
  std::atomic<bool> cancel{true};
  o.cancel = &cancel;
  done = 0;
  BOOST_CHECK_THROW(contacts(A, B, o), Cancelled);
  BOOST_CHECK_THROW(contacts_exact_self(A, o), Cancelled);
  BOOST_TEST(done == 0u);
  // cancelled from stage 4 after 10 pairs: at most the pairs already started finish
  cancel = false;
  o.progress = [&](std::size_t n, std::size_t) {
    if ((done += n) >= 10) cancel = true;
  };
  BOOST_CHECK_THROW(contacts(A, B, o), Cancelled);
  BOOST_TEST(done >= 10u);
  BOOST_TEST(done < 10u + 4 * std::thread::hardware_concurrency() + 4);
}

BOOST_AUTO_TEST_CASE(touching_meshes_report_no_pair) {
  // Two boxes on either side of the plane x = 1, meshed independently.
  const Contacts<double> t = contacts(load("touching-a.msh"), load("touching-b.msh"));
  BOOST_TEST(t.pairs.empty());
  // A ball and the box around it, one conforming mesh split in two: many boxes overlap, the
  // exact decision finds that no interiors do.
  const Contacts<double> c = contacts(load("conforming-a.msh"), load("conforming-b.msh"));
  BOOST_TEST(c.box_pairs > 1000u);
  BOOST_TEST(c.pairs.empty());
}

BOOST_AUTO_TEST_CASE(reference_engine_on_a_tiny_mesh_is_exact) {
  const Mesh A = load("tiny-a.msh"), B = load("tiny-b.msh");
  const Contacts<Rational> e = contacts_exact(A, B, computing(kAllVariants));
  const Contacts<Rational> plain = contacts_exact(A, B);  // default variants: no definitions §9 search
  const Contacts<double> f = contacts(A, B, computing(kAllVariants));
  BOOST_TEST(!e.pairs.empty());
  BOOST_TEST((pairs_of(e) == pairs_of(f)));
  BOOST_TEST((pairs_of(plain) == pairs_of(f)));
  BOOST_TEST((pairs_of(e) == brute_force(A, &B)));
  const Rational contract(1, 1000000000);  // definitions §8: 1e-9 relative
  std::size_t strictly_inside = 0;
  for (std::size_t i = 0; i < e.pairs.size(); ++i) {
    const auto& x = e.pairs[i].result;
    BOOST_REQUIRE(!x.error);
    const TetVertices Ta = element(A, e.pairs[i].a), Tb = element(B, e.pairs[i].b);
    const PairResult<Rational> r = reference::solve_pair(TetPair{"", {}, Ta, Tb});
    BOOST_TEST(x.intersecting);
    for (std::size_t k = 0; k < kValueCount; ++k) {
      BOOST_TEST(record_value(x, k) == record_value(r, k));
      BOOST_TEST(record_value(plain.pairs[i].result, k) == record_value(r, k));
      // definitions §8 for the fast engine on the same pair, checked exactly.
      const Rational fast_value(record_value(f.pairs[i].result, k));
      const Rational err = abs(fast_value - record_value(x, k));
      BOOST_TEST(err <= contract * record_value(x, k), kValueKeys[k]);
    }
    BOOST_TEST((x.q1_A == r.q1_A && x.q1_B == r.q1_B));
    // definitions §9 with kGlobal: pdd::reference::solve_pair's exact witness and proved bound, an
    // interval below pdd2_relaxed no wider than 1e-12 of it, and the fast value inside it up
    // to definitions §8 (the fast engine's §9 contract).
    BOOST_REQUIRE(x.pdd2_global_lower);
    BOOST_REQUIRE(x.pdd2_global_normal);
    BOOST_TEST(x.pdd2_global == r.pdd2_global);
    BOOST_TEST(*x.pdd2_global_lower == *r.pdd2_global_lower);
    BOOST_TEST((*x.pdd2_global_normal == *r.pdd2_global_normal));
    BOOST_TEST((x.q1_A_global == r.q1_A_global && x.q1_B_global == r.q1_B_global));
    const Rational lower = *x.pdd2_global_lower, upper = x.pdd2_global;
    BOOST_TEST(lower > 0);
    BOOST_TEST(lower <= upper);
    BOOST_TEST(upper <= x.pdd2_relaxed);
    BOOST_TEST(upper - lower <= Rational(1, 1000000000000) * upper);
    const Rational fast_global(f.pairs[i].result.pdd2_global);
    BOOST_TEST(fast_global >= lower * (1 - contract));
    BOOST_TEST(fast_global <= upper * (1 + contract));
    if (lower <= fast_global && fast_global <= upper) ++strictly_inside;
    // Without kGlobal the search does not run: the fields are cleared (mesh.h).
    const auto& y = plain.pairs[i].result;
    BOOST_TEST(y.pdd2_global == 0);
    BOOST_TEST(!y.pdd2_global_lower);
    BOOST_TEST(!y.pdd2_global_normal);
    BOOST_TEST((y.q1_A_global == exact_pose(Ta) && y.q1_B_global == exact_pose(Tb)));
  }
  BOOST_TEST_MESSAGE("fast pdd2_global strictly inside the exact interval on " << strictly_inside << " of "
                                                                               << e.pairs.size() << " pairs");
}

BOOST_AUTO_TEST_CASE(vtk_output_reads_back) {
  const Mesh A = load("sphere-a.msh"), B = load("sphere-b.msh");
  const Contacts<double> c = contacts(A, B);
  const std::string path = "mesh_test_out.vtk";
  write_vtk(path, A, B, c, kDefaultVariants);
  const Mesh both = read_mesh(path);  // our own reader: the cells are A's then B's
  BOOST_REQUIRE(both.tets.size() == A.tets.size() + B.tets.size());
  BOOST_TEST((element(both, 0) == element(A, 0)));
  BOOST_TEST((element(both, A.tets.size()) == element(B, 0)));
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : {"SCALARS partners int", "SCALARS max_pdd2 double", "VECTORS displacement double"})
    BOOST_TEST(contains(text, key));
  BOOST_TEST(!contains(text, "max_pdd2_global"));
  // With kGlobal: max_pdd2_global, each cell's largest pdd2_global over its pairs.
  const Mesh a = load("tiny-a.msh"), b = load("tiny-b.msh");
  const Contacts<double> g = contacts(a, b, computing(kRigid | kGlobal));
  write_vtk(path, a, b, g, kRigid | kGlobal);
  std::ifstream gin(path);
  const std::string gtext((std::istreambuf_iterator<char>(gin)), std::istreambuf_iterator<char>());
  const std::size_t at = gtext.find("SCALARS max_pdd2_global double 1\nLOOKUP_TABLE default\n");
  BOOST_REQUIRE(at != std::string::npos);
  std::istringstream cells(gtext.substr(at));
  std::string line;
  std::getline(cells, line), std::getline(cells, line);
  double biggest = 0;
  for (std::size_t i = 0; i < a.tets.size() + b.tets.size(); ++i) {
    double v = -1;
    cells >> v;
    biggest = std::max(biggest, v);
  }
  double want = 0;
  for (const auto& p : g.pairs) want = std::max(want, p.result.pdd2_global);
  BOOST_TEST(want > 0.0);
  BOOST_TEST(biggest == want);
}

BOOST_AUTO_TEST_CASE(variant_names_parse_and_print) {
  BOOST_TEST(parse_variants("global") == unsigned(kGlobal));
  BOOST_TEST(parse_variants("rigid,global,accel1") == unsigned(kRigid | kGlobal | kAccel1));
  BOOST_TEST((parse_variants("all") & kGlobal) != 0u);
  BOOST_TEST(parse_variants("all") == (parse_variants("rigid,eq11,static,pdd2,relaxed,accel1,accel6") | kGlobal));
  BOOST_TEST((kDefaultVariants & kGlobal) == 0u);  // tens of microseconds a pair: asked for only
  BOOST_TEST(variant_names(kAllVariants) == "rigid,eq11,static,pdd2,relaxed,accel1,accel6,global");
  BOOST_TEST(variant_names(parse_variants("global,rigid")) == "rigid,global");
  for (const char* bad : {"bogus", "Global", ",global", "pdd2_global", ""}) {
    BOOST_TEST_CONTEXT(bad) {
      std::string what;
      try {
        parse_variants(bad);
      } catch (const std::invalid_argument& e) {
        what = e.what();
      }
      BOOST_TEST(!what.empty());
    }
  }
  std::string what = "(no exception)";
  try {
    parse_variants("rigid,bogus");
  } catch (const std::invalid_argument& e) {
    what = e.what();
  }
  BOOST_TEST(what == "unknown variant 'bogus' (rigid, eq11, static, pdd2, relaxed, accel1, accel6, global, all)");
}
