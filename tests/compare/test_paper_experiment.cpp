// The statistics of `pdd paper` on hand-made results (values derived in the comments).
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "fixtures.h"
#include "pdd/compare/family_global_cost.h"
#include "pdd/compare/paper_experiment.h"
#include "pdd/compare/paper_figures.h"
#include "pdd/reference/solve_exact.h"

using namespace pdd;
using namespace pdd::compare;

namespace {
PairResult<double> result(double pd2, double e11, double st, double def, double a1, double a6, double rel,
                          const char* rigid_dir, const char* pdd2_dir) {
  PairResult<double> r;
  r.intersecting = true;
  r.rigid_pd2 = pd2, r.eq11_pd2 = e11, r.pdd2_static = st, r.pdd2 = def;
  r.pdd2_accel1 = a1, r.pdd2_accel6 = a6, r.pdd2_relaxed = rel;
  r.rigid_dir = DirectionLabel::parse(rigid_dir);
  r.pdd2_dir = DirectionLabel::parse(pdd2_dir);
  return r;
}
}  // namespace

BOOST_AUTO_TEST_CASE(ratios_are_square_roots_of_squared_ratios) {
  // Pair 1: PD^2 = 4, static 1 -> ratio 1/2; def 0.25 -> 1/4. Pair 2: PD^2 = 16, static 4 ->
  // 1/2; def 9 -> 3/4. Static ratios {1/2, 1/2}: mean 1/2, std 0. Def ratios {1/4, 3/4}: mean
  // 1/2, sample std sqrt(((1/4)^2 + (1/4)^2) / 1) = sqrt(1/8).
  std::vector<PairResult<double>> rs = {result(4, 1, 1, 0.25, 0.25, 0.25, 0.25, "FV:0", "FV:0"),
                                        result(16, 16, 4, 9, 16, 9, 9, "FV:1", "EE:0:1")};
  PairResult<double> skipped;  // not intersecting: skipped and counted
  rs.push_back(skipped);
  const PaperStats s = paper_statistics(rs, [](double x) { return x; });
  BOOST_TEST(s.pairs == 2u);
  BOOST_TEST(s.skipped == 1u);
  BOOST_TEST(s.over_pd[0].mean == 0.5);
  BOOST_TEST(s.over_pd[0].std == 0.0);
  BOOST_TEST(s.over_pd[1].mean == 0.5);
  BOOST_TEST(s.over_pd[1].std == std::sqrt(0.125), boost::test_tools::tolerance(1e-15));
  // Over E11: pair 1 E11^2 = 1 -> def ratio sqrt(0.25/1) = 1/2; pair 2 -> 3/4: mean 5/8.
  BOOST_TEST(s.over_e11[1].mean == 0.625);
  BOOST_TEST(s.rigid_is_optimal == 1u);      // only pair 1 has rigid_dir == pdd2_dir
  BOOST_TEST(s.optimum_in_first_six == 2u);  // accel6 == pdd2 on both
}

BOOST_AUTO_TEST_CASE(volumes_of_both_tetrahedra) {
  // The unit corner tetrahedron has volume 1/6; B twice as large in each direction: 8/6.
  TetPair p;
  p.A = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  p.B = {{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}}};
  const auto v = tetrahedron_volumes({p});
  BOOST_TEST(v.size() == 2u);
  BOOST_TEST(v[0] == 1.0 / 6, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(v[1] == 8.0 / 6, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(global_statistics_by_hand) {
  // One pair: PD^2 = 4, pdd2 = 2, pdd2_relaxed = 1.5, pdd2_global = 1 along (1, 0, 0).
  // PD_d_global / PD = sqrt(1/4) = 1/2; pdd2 / global = 2; relaxed / global = 1.5 (so the
  // optimum is not a candidate's). Candidates (0, 1, 0) at 90 degrees and (1, 1, 0) at 45: the
  // nearest is 45 degrees. The second candidate is given as (1e205, 1e205, 0), whose squared
  // length overflows a double (as a candidate of a pair scaled by 2^450 does: an adversarial
  // family pair once read 180 degrees here), and the exact normal as (2^1100, 0, 0), which no
  // double holds: neither may change the angle.
  PairResult<reference::Rational> r;
  r.intersecting = true;
  r.rigid_pd2 = 4, r.pdd2 = 2, r.pdd2_relaxed = 1.5, r.pdd2_global = 1;
  reference::Rational huge = 1;
  for (int i = 0; i < 1100; ++i) huge *= 2;
  r.pdd2_global_normal = std::array<reference::Rational, 3>{huge, 0, 0};
  PairResult<reference::Rational> skipped;  // not intersecting: not counted
  const std::vector<PairResult<reference::Rational>> rs = {r, skipped};
  const std::vector<TetPair> pairs(2);
  auto candidates = [](const TetPair&) {
    return std::vector<std::array<double, 3>>{{0, 1, 0}, {1e205, 1e205, 0}};
  };
  const GlobalStats s = global_statistics(
      pairs, rs, [](const reference::Rational& q) { return CGAL::to_double(q); }, candidates);
  BOOST_TEST(s.pairs == 1u);
  BOOST_TEST(s.global_over_pd.mean == 0.5);
  BOOST_TEST(s.pdd2_over_global.mean == 2.0);
  BOOST_TEST(s.relaxed_over_global.mean == 1.5);
  BOOST_TEST(s.at_candidate == 0u);
  BOOST_TEST(s.angle_degrees.mean == 45.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(candidate_normals_survive_extreme_scales) {
  // A paper-like pair and the same pair scaled by 2^450 and 2^-450 (exact): the candidate
  // directions are the same up to a positive factor, so after rounding each one's direction
  // must agree to a few ulps (the unscaled cross products' components are far from overflow).
  TetPair p;
  p.A = {{{0, 0, 0}, {3, 0.5, 0}, {0.25, 2, 0.75}, {0.5, 0.5, 4}}};
  p.B = {{{1, 1, 1}, {4, 1.5, 0.25}, {1.75, 3, 2}, {0.5, 2.5, 3.5}}};
  for (int e : {450, -450}) {
    TetPair q = p;
    for (auto* T : {&q.A, &q.B})
      for (auto& v : *T)
        for (double& x : v) x = std::ldexp(x, e);
    const auto a = candidate_normals_rounded(p), b = candidate_normals_rounded(q);
    BOOST_TEST_REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      auto unit = [](std::array<double, 3> v) {
        const double m = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
        for (double& x : v) x /= m;
        return v;
      };
      const auto u = unit(a[i]), w = unit(b[i]);
      for (int k = 0; k < 3; ++k) BOOST_TEST(std::abs(u[k] - w[k]) <= 1e-15, "scale 2^" << e << " candidate " << i);
    }
  }
}

BOOST_AUTO_TEST_CASE(family_global_costs_of_the_shipped_families) {
  // Every family file with its golden file; the fast engine's statistics against the exact
  // ones read from the golden files. Where both engines count the same pairs, definitions §8 puts
  // each fast value within 1e-9 of the exact one, so each squared ratio within ~2e-9 and so
  // their means and maxima; the same pairs have their optimum at a candidate's.
  const auto costs = family_global_costs(PDD_FIXTURES_DIR);
  const auto files = pdd::test::property_fixture_files();
  const auto families = std::count_if(files.begin(), files.end(), [](const std::string& f) { return f.rfind("families/", 0) == 0; });
  BOOST_TEST_REQUIRE(costs.size() == std::size_t(families));
  for (const FamilyGlobalCost& f : costs) {
    BOOST_TEST_CONTEXT(f.family) {
      BOOST_TEST(f.exact.pairs <= f.intersecting);
      BOOST_TEST(f.fast.pairs <= f.exact.pairs);  // the fast engine may reject (definitions §8), never add
      if (f.family == "disjoint" || f.family == "touching") BOOST_TEST(f.exact.pairs == 0u);
      if (f.fast.pairs != f.exact.pairs || f.fast.pairs == 0) continue;
      auto close = [](double x, double y) { return std::abs(x - y) <= 1e-8 * y; };
      BOOST_TEST(close(f.fast.relaxed_over_global.mean, f.exact.relaxed_over_global.mean));
      BOOST_TEST(close(f.fast.pdd2_over_global.mean, f.exact.pdd2_over_global.mean));
      BOOST_TEST(close(f.fast.global_over_pd.mean, f.exact.global_over_pd.mean));
      BOOST_TEST(f.fast.at_candidate == f.exact.at_candidate);
      for (double a : f.fast.angle_degrees.values) BOOST_TEST((a >= 0 && a <= 180));
    }
  }
}

// pair_before_after.vtk: every cell of a rest tetrahedron is positive by VTK's convention
// ((p1 - p0) . ((p2 - p0) x (p3 - p0)) > 0, read back from the file), whichever orientation the
// pair's vertices have; here A is negatively ordered and B positively.
BOOST_AUTO_TEST_CASE(pair_vtk_cells_follow_vtk_orientation) {
  PairConfigurations c;
  c.name = "poke";
  c.A_rest = {{{0, 0, 0}, {0, 10, 0}, {10, 0, 0}, {0, 0, 10}}};  // negative as given
  c.B_rest = {{{1, 1, -1}, {3, 1, -1}, {1, 3, -1}, {1.5, 1.5, 0.5}}};
  c.B_static = c.B_deformable = c.B_rigid = c.B_rest;
  c.A_deformable = c.A_rest;
  const std::string path = "paper_pair_test.vtk";
  write_vtk(path, c);
  std::ifstream in(path);
  std::string line;
  std::vector<std::array<double, 3>> points;
  while (std::getline(in, line) && line.rfind("POINTS", 0) != 0) {
  }
  for (int i = 0; i < 24; ++i) {
    std::array<double, 3> p{};
    in >> p[0] >> p[1] >> p[2];
    points.push_back(p);
  }
  while (std::getline(in, line) && line.rfind("CELLS", 0) != 0) {
  }
  for (int k = 0; k < 6; ++k) {
    int n = 0, v[4];
    in >> n >> v[0] >> v[1] >> v[2] >> v[3];
    BOOST_REQUIRE(n == 4);
    double e[3][3];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) e[i][d] = points[v[i + 1]][d] - points[v[0]][d];
    const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    BOOST_TEST(det > 0, "cell " << k);
  }
}

namespace {
std::string file_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
// A PNG file ends with its IEND chunk: length 0, "IEND", CRC ae 42 60 82 (PNG specification).
bool complete_png(const std::string& bytes) {
  static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  return bytes.size() > 12 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 &&
         bytes.compare(bytes.size() - 12, 12, iend) == 0;
}
std::vector<std::string> partial_files(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().find(".partial-") != std::string::npos) out.push_back(e.path().string());
  return out;
}
}  // namespace

// The pictures of `pdd paper` replace old ones whole: written under a temporary name and renamed
// when gnuplot succeeded; when it fails (here: not found on PATH) the old picture stays byte for
// byte (also when gnuplot dies while writing it), and no temporary file is left either way. The script still draws to its own name when
// run by hand (its variable `out` defaults to it).
BOOST_AUTO_TEST_CASE(paper_figures_replace_old_files_whole) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("pdd-paper-figures-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"fig3_histograms.png", "fig3_histograms.dat", "fig3_histograms.gp"})
    std::ofstream(dir / name) << "old " << name;
  std::vector<PairResult<double>> rs = {result(4, 1, 1, 0.25, 0.25, 0.25, 0.25, "FV:0", "FV:0"),
                                        result(16, 16, 4, 9, 16, 9, 9, "FV:1", "EE:0:1")};
  const PaperStats s = paper_statistics(rs, [](double x) { return x; });
  std::string why;

  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", (dir / "no-programs-here").c_str(), 1);
  const bool drawn_without_gnuplot = write_fig3(dir.string(), s, why);
  setenv("PATH", path.c_str(), 1);
  BOOST_TEST(!drawn_without_gnuplot);
  BOOST_TEST(why.find("gnuplot failed") != std::string::npos, why);
  BOOST_TEST(file_text(dir / "fig3_histograms.png") == "old fig3_histograms.png");
  BOOST_TEST(file_text(dir / "fig3_histograms.dat").rfind("# bin_center", 0) == 0u);  // the data is new
  BOOST_TEST(partial_files(dir).empty());

  // gnuplot stopped while writing its picture: a stand-in runs the real one, passes on the
  // first 100 bytes of what it drew (to its output, a file or standard output) and fails. The
  // picture under the final name is still the old one.
  const fs::path bin = dir / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "gnuplot") << "#!/bin/sh\nPATH='" << path << "' gnuplot \"$@\" | head -c 100\n"
                                 << "exit 1\n";
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  setenv("PATH", (bin.string() + ":" + path).c_str(), 1);
  const bool drawn_cut = write_fig3(dir.string(), s, why);
  setenv("PATH", path.c_str(), 1);
  BOOST_TEST(!drawn_cut);
  BOOST_TEST(file_text(dir / "fig3_histograms.png") == "old fig3_histograms.png");
  BOOST_TEST(partial_files(dir).empty());

  BOOST_REQUIRE(write_fig3(dir.string(), s, why));
  BOOST_TEST(complete_png(file_text(dir / "fig3_histograms.png")));
  BOOST_TEST(partial_files(dir).empty());

  fs::remove(dir / "fig3_histograms.png");
  const std::string by_hand = "cd '" + dir.string() + "' && gnuplot fig3_histograms.gp 2>/dev/null";
  BOOST_REQUIRE(std::system(by_hand.c_str()) == 0);
  BOOST_TEST(complete_png(file_text(dir / "fig3_histograms.png")));
  fs::remove_all(dir);
}
