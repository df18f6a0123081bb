// tests/mesh — pdd::mesh::write_mesh and write_resolution_vtk (include/pdd/mesh.h):
//   round trip: every shipped mesh, written as Gmsh 4.1 (.msh) and legacy VTK (.vtk) and read
//            back by read_mesh, gives the same tetrahedra and every coordinate bit for bit, also
//            for doubles whose shortest decimal is long (0.1 + 0.2, nextafter steps), -0,
//            subnormals, the largest and smallest normal doubles, and (.msh) nan and inf;
//   failures: an unknown extension names the path; a missing folder, /dev/full and a
//            position count that does not match throw and leave nothing (no file, no
//            temporary file, an existing file unchanged); a device is written in place, never
//            renamed over;
//   ParaView file: write_resolution_vtk's points read back as A's then B's new positions and
//            its cells as A's then B's tetrahedra; its volume ratios the same at any scale.
#define BOOST_TEST_MODULE write_mesh
#include <boost/test/unit_test.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "pdd/mesh.h"

using namespace pdd;
using namespace pdd::mesh;
namespace fs = std::filesystem;

namespace {

const std::string kDir = std::string(PDD_FIXTURES_DIR) + "/meshes/";

// A fresh empty folder for one test.
fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("pdd-write-mesh-" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Writes m at p to `path`, reads it back, and checks connectivity and coordinates (bit for bit;
// nan: any nan, as strtod does not keep a payload).
void round_trip(const Mesh& m, const std::vector<Vec3d>& p, const std::string& path) {
  write_mesh(path, m, p);
  const Mesh r = read_mesh(path);
  BOOST_TEST_CONTEXT(path) {
    BOOST_TEST_REQUIRE(r.vertices.size() == p.size());
    BOOST_TEST_REQUIRE(r.tets.size() == m.tets.size());
    for (std::size_t i = 0; i < m.tets.size(); ++i) BOOST_TEST((r.tets[i] == m.tets[i]), "tetrahedron " << i);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int k = 0; k < 3; ++k)
        if (!(std::isnan(p[i][k]) ? std::isnan(r.vertices[i][k]) : same_bits(p[i][k], r.vertices[i][k]))) {
          if (!differ++) BOOST_ERROR("vertex " << i << " coordinate " << k << ": wrote " << p[i][k] << ", read " << r.vertices[i][k]);
        }
    BOOST_TEST(differ == 0u);
  }
  for (const auto& e : fs::directory_iterator(fs::path(path).parent_path()))
    BOOST_TEST(e.path().filename().string().find(".partial-") == std::string::npos, "left behind: " << e.path());
}

}  // namespace

BOOST_AUTO_TEST_CASE(shipped_meshes_round_trip) {
  const fs::path d = scratch("shipped");
  for (const char* name : {"sphere-a.msh", "sphere-b.msh", "sphere-a.vtk", "torus.msh", "box.vtk",
                           "two-spheres.msh", "slivers.msh", "tiny-a.msh"}) {
    const Mesh m = read_mesh(kDir + name);
    round_trip(m, m.vertices, (d / (std::string(name) + ".msh")).string());
    round_trip(m, m.vertices, (d / (std::string(name) + ".vtk")).string());
  }
}

BOOST_AUTO_TEST_CASE(awkward_doubles_round_trip) {
  const fs::path d = scratch("awkward");
  Mesh m = read_mesh(kDir + "tiny-a.msh");
  std::vector<Vec3d> p = m.vertices;
  const double special[] = {0.1 + 0.2,
                            std::nextafter(1.0, 2.0),
                            std::nextafter(1.0, 0.0),
                            -0.0,
                            std::numeric_limits<double>::denorm_min(),
                            -std::numeric_limits<double>::denorm_min() * 3,
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max(),
                            1.0 / 3.0,
                            123456789.12345678,
                            -2.5e-300};
  // Every vertex: the specials in turn, and coordinates scaled by 1 + 1e-13 (17 digits needed).
  const std::size_t n = std::size(special);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = (i + k) % 2 ? special[(3 * i + k) % n] : p[i][k] * (1 + 1e-13);
  round_trip(m, p, (d / "a.msh").string());
  round_trip(m, p, (d / "a.vtk").string());
  // Not finite: read_mesh reads them back (Gmsh file; VTK readers reject them, so not tested there).
  p[0] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};
  round_trip(m, p, (d / "nan.msh").string());
}

BOOST_AUTO_TEST_CASE(unknown_extension_names_the_path) {
  const fs::path d = scratch("ext");
  const Mesh m = read_mesh(kDir + "tiny-a.msh");
  for (const std::string name : {"a.obj", "a", "a.msh.gz"}) {
    const std::string path = (d / name).string();
    try {
      write_mesh(path, m, m.vertices);
      BOOST_ERROR("no exception for " << path);
    } catch (const std::runtime_error& e) {
      BOOST_TEST(std::string(e.what()).find("'" + path + "'") != std::string::npos, e.what());
      BOOST_TEST(std::string(e.what()).find(".msh") != std::string::npos, e.what());
    }
    BOOST_TEST(!fs::exists(path));
  }
  // Case does not matter.
  write_mesh((d / "UPPER.MSH").string(), m, m.vertices);
  BOOST_TEST(read_mesh((d / "UPPER.MSH").string()).tets.size() == m.tets.size());
}

BOOST_AUTO_TEST_CASE(failures_leave_nothing) {
  const fs::path d = scratch("fail");
  const Mesh m = read_mesh(kDir + "tiny-a.msh");
  BOOST_CHECK_THROW(write_mesh((d / "no" / "such" / "a.msh").string(), m, m.vertices), std::runtime_error);
  BOOST_TEST(!fs::exists(d / "no"));
  // An existing file is replaced whole, or left as it was.
  const std::string keep = (d / "keep.msh").string();
  std::ofstream(keep) << "old contents\n";
  std::vector<Vec3d> fewer(m.vertices.begin(), m.vertices.end() - 1);
  BOOST_CHECK_THROW(write_mesh(keep, m, fewer), std::invalid_argument);
  std::ifstream in(keep);
  std::stringstream text;
  text << in.rdbuf();
  BOOST_TEST(text.str() == "old contents\n");
  write_mesh(keep, m, m.vertices);
  BOOST_TEST(read_mesh(keep).vertices.size() == m.vertices.size());
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    ++files;
    BOOST_TEST(e.path().filename() == "keep.msh");
  }
  BOOST_TEST(files == 1u);
  // A device is written in place (renaming over it would replace the device node): /dev/full
  // refuses the data, /dev/null takes it; both stay character devices.
  struct stat st {};
  if (::stat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode)) {
    // /dev/null has no extension: through a symbolic link named .msh, which is also written in place.
    const fs::path link = d / "null.msh";
    fs::create_symlink("/dev/null", link);
    write_mesh(link.string(), m, m.vertices);
    BOOST_TEST(fs::is_symlink(link));
    BOOST_TEST(::stat("/dev/null", &st) == 0);
    BOOST_TEST(S_ISCHR(st.st_mode));
    const fs::path full = d / "full.msh";
    fs::create_symlink("/dev/full", full);
    BOOST_CHECK_THROW(write_mesh(full.string(), m, m.vertices), std::runtime_error);
    BOOST_TEST(fs::is_symlink(full));
    BOOST_TEST(::stat("/dev/full", &st) == 0);
    BOOST_TEST(S_ISCHR(st.st_mode));
  }
}

BOOST_AUTO_TEST_CASE(resolution_vtk_reads_back) {
  const fs::path d = scratch("vtk");
  const Mesh A = read_mesh(kDir + "tiny-a.msh"), B = read_mesh(kDir + "tiny-b.msh");
  std::vector<Vec3d> a1 = A.vertices, b1 = B.vertices;
  for (auto& v : b1) v[0] += 0.25;
  ResolveReport report;
  report.remaining_pairs = {{0, 1}};
  report.bad_elements = {{'B', 2}};
  const std::string path = (d / "both.vtk").string();
  write_resolution_vtk(path, A, a1, B, b1, report);
  const Mesh r = read_mesh(path);
  BOOST_TEST_REQUIRE(r.vertices.size() == a1.size() + b1.size());
  BOOST_TEST_REQUIRE(r.tets.size() == A.tets.size() + B.tets.size());
  for (std::size_t i = 0; i < a1.size(); ++i)
    for (int k = 0; k < 3; ++k) BOOST_TEST(same_bits(r.vertices[i][k], a1[i][k]));
  for (std::size_t i = 0; i < b1.size(); ++i)
    for (int k = 0; k < 3; ++k) BOOST_TEST(same_bits(r.vertices[a1.size() + i][k], b1[i][k]));
  for (std::size_t i = 0; i < B.tets.size(); ++i)
    for (int v = 0; v < 4; ++v) BOOST_TEST(r.tets[A.tets.size() + i][v] == B.tets[i][v] + a1.size());
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  for (const char* field : {"VECTORS displacement double", "SCALARS volume_ratio double 1",
                            "SCALARS remaining int 1", "SCALARS bad int 1", "SCALARS mesh int 1"})
    BOOST_TEST(text.str().find(field) != std::string::npos, field);
}

// The volume_ratio field of a resolution scaled by 2^e is the unscaled one, line for line: the
// ratios are taken on edges scaled to the element's size (V ~ L^3 would leave the double range
// at e = +-400 and show 0).
BOOST_AUTO_TEST_CASE(resolution_vtk_volume_ratios_at_any_scale) {
  const fs::path d = scratch("vtk-scale");
  auto volume_ratios = [&](int e) {
    Mesh A = read_mesh(kDir + "tiny-a.msh"), B = read_mesh(kDir + "tiny-b.msh");
    std::vector<Vec3d> a1 = A.vertices, b1 = B.vertices;
    b1[0][2] += 0.25;  // B's elements at vertex 0 change volume
    for (auto* p : {&A.vertices, &B.vertices, &a1, &b1})
      for (Vec3d& v : *p)
        for (double& c : v) c = std::ldexp(c, e);
    const std::string path = (d / ("both" + std::to_string(e) + ".vtk")).string();
    write_resolution_vtk(path, A, a1, B, b1, ResolveReport{});
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const std::string all = text.str(), head = "SCALARS volume_ratio double 1\nLOOKUP_TABLE default\n";
    const std::size_t from = all.find(head) + head.size();
    return all.substr(from, all.find("SCALARS", from) - from);
  };
  const std::string unit = volume_ratios(0);
  BOOST_TEST(unit.find("\n1\n") != std::string::npos);  // unchanged elements
  BOOST_TEST(unit.find("\n0\n") == std::string::npos);  // no element shown as 0
  for (int e : {-400, 400}) BOOST_TEST(volume_ratios(e) == unit);
}
