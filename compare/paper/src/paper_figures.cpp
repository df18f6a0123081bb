#include "pdd/compare/paper_figures.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <sys/wait.h>

#include "pdd/io/output.h"
#include "pdd/reference/candidate_table.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {
namespace {

TetVertices to_doubles(const reference::ExactTet& t) {
  TetVertices out;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = CGAL::to_double(t[i][k]);
  return out;
}

// Runs `command` with /bin/sh; its standard output, or nullopt when it could not start or did
// not exit with 0. Not std::system: that ignores SIGINT in pdd while it waits, so Ctrl-C during
// a picture would stop gnuplot and be lost to pdd (streaming.h answers signals). popen and
// pclose leave the signal dispositions alone.
std::optional<std::string> shell_output(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return std::nullopt;
  std::string out;
  char buf[1 << 16];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  const int status = ::pclose(pipe);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return out;
}

// gnuplot on DIR/SCRIPT, its picture read from its standard output (the script's variable
// `out`, set to /dev/stdout here, PNG itself when the script is run by hand) and written to
// DIR/PNG as io::write_file writes text: whole or not at all. A gnuplot that fails or is stopped
// leaves the old picture; nothing of it reaches the disk before it has finished.
bool run_gnuplot(const std::string& dir, const std::string& script, const std::string& png, std::string& why) {
  const std::string log = script.substr(0, script.find('.')) + ".log";
  const std::string cmd = "cd '" + dir + "' && gnuplot -e \"out='/dev/stdout'\" '" + script + "' 2> '" + log + "'";
  const std::optional<std::string> picture = shell_output(cmd);
  if (!picture || picture->empty()) {
    why = "gnuplot failed on " + dir + "/" + script + " (see " + dir + "/" + log + "; is gnuplot installed?)";
    return false;
  }
  if (auto failed = io::write_file(dir + "/" + png, *picture)) {
    why = *failed;
    return false;
  }
  return true;
}

// The whole text to `path` or nothing (io::write_file: a temporary file and a rename). A file
// that could not be written in full is an error of the whole run, not a missing picture.
void write_whole(const std::string& path, const std::ostringstream& text) {
  if (auto why = io::write_file(path, text.str())) throw std::runtime_error(*why);
}

// The script's first lines: the terminal and the picture's name (`out`, see run_gnuplot).
std::string png_output(const std::string& size, const std::string& png, int font = 11) {
  return "set terminal pngcairo size " + size + " font 'Sans," + std::to_string(font) + "'\nif (!exists('out')) out = '" + png +
         "'\nset output out\n";
}

// The six edges of a tetrahedron as gnuplot line segments (blank line between segments).
void write_edges(std::ostream& o, const TetVertices& t) {
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b)
      o << t[a][0] << ' ' << t[a][1] << ' ' << t[a][2] << '\n'
        << t[b][0] << ' ' << t[b][1] << ' ' << t[b][2] << "\n\n";
}

}  // namespace

PairConfigurations pair_configurations(const TetPair& pair) {
  using namespace reference;
  const ExactResult r = solve_exact(pair, {QpFormulation::Reduced});
  const ExactPair p = to_exact(pair);
  PairConfigurations c{pair.name, pair.A, pair.B, pair.B, pair.A, pair.B, pair.B,
                       std::sqrt(CGAL::to_double(r.rigid_pd2)), std::sqrt(CGAL::to_double(r.pdd2_static)),
                       std::sqrt(CGAL::to_double(r.pdd2))};
  if (!r.intersecting) return c;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      c.A_deformable[i][k] = CGAL::to_double(r.q1_A[i][k]), c.B_deformable[i][k] = CGAL::to_double(r.q1_B[i][k]);
  const CandidateTableOptions reduced{QpFormulation::Reduced};
  if (const auto st = candidate_row(p, *r.pdd2_static_dir, reduced))
    c.B_static = to_doubles(st->static_case->q1_B);
  if (const auto rg = candidate_row(p, *r.rigid_dir, reduced)) {
    // B + (D / n.n) n: translation by PD along n
    const Vector& n = rg->direction.n;
    const Vector v = (rg->depth / n.squared_length()) * n;
    ExactTet moved = p.B;
    for (auto& x : moved) x = x + v;
    c.B_rigid = to_doubles(moved);
  }
  return c;
}

bool write_fig3(const std::string& dir, const PaperStats& s, std::string& why) {
  constexpr int kBins = 60;
  constexpr double kMax = 1.2;  // PD_d / PD <= 1 for static (<= 1/sqrt 2 for case 2); margin
  std::ostringstream dat;
  dat << "# bin_center";
  for (const char* v : kPaperVariants) dat << " \"" << v << "\"";
  dat << "\n";
  std::vector<std::array<double, 5>> counts(kBins);
  for (int k = 0; k < 5; ++k)
    for (double x : s.over_pd[k].values) {
      const int b = std::min(kBins - 1, int(x / kMax * kBins));
      counts[b][k] += 100.0 / double(s.over_pd[k].n);  // percent of pairs
    }
  for (int b = 0; b < kBins; ++b) {
    dat << (b + 0.5) * kMax / kBins;
    for (int k = 0; k < 5; ++k) dat << ' ' << counts[b][k];
    dat << "\n";
  }
  write_whole(dir + "/fig3_histograms.dat", dat);  // gnuplot reads it below
  std::ostringstream gp;
  gp << png_output("1500,420", "fig3_histograms.png")
     << "set multiplot layout 1,3 title 'PD_d / PD over " << s.pairs << " random intersecting pairs (cf. paper Fig. 3)'\n"
     << "set style fill solid 0.6 border -1\nset boxwidth " << kMax / kBins << "\nset xrange [0:1]\n"
     << "set xlabel 'PD_d / PD'\nset ylabel '% of pairs'\nset grid ytics\n";
  const int panels[3] = {0, 1, 2};
  const char* colours[3] = {"#4477aa", "#cc3311", "#228833"};
  for (int i = 0; i < 3; ++i) {
    const int k = panels[i];
    gp << std::fixed << std::setprecision(2) << "set title '" << kPaperVariants[k] << ": mean "
       << 100 * s.over_pd[k].mean << "%, std " << 100 * s.over_pd[k].std << "%'\n"
       << "plot 'fig3_histograms.dat' using 1:" << k + 2 << " with boxes lc rgb '" << colours[i]
       << "' notitle\n";
  }
  gp << "unset multiplot\n";
  write_whole(dir + "/fig3_histograms.gp", gp);
  return run_gnuplot(dir, "fig3_histograms.gp", "fig3_histograms.png", why);
}

bool write_global_figure(const std::string& dir, const GlobalStats& s, std::string& why) {
  constexpr int kBins = 60;
  double top = 1.0;
  for (const RatioStats* r : {&s.relaxed_over_global, &s.pdd2_over_global})
    for (double x : r->values) top = std::max(top, x);
  top = std::min(top, 4.0);  // the tail beyond 4 is counted in the last bin
  std::ostringstream dat;
  dat << "# bin_center \"pdd2_relaxed / pdd2_global\" \"pdd2 / pdd2_global\" (% of pairs)\n";
  std::vector<std::array<double, 2>> counts(kBins);
  const RatioStats* cols[2] = {&s.relaxed_over_global, &s.pdd2_over_global};
  for (int k = 0; k < 2; ++k)
    for (double x : cols[k]->values) {
      const int b = std::clamp(int((x - 1.0) / (top - 1.0 + 1e-300) * kBins), 0, kBins - 1);
      counts[b][k] += 100.0 / double(cols[k]->n);
    }
  for (int b = 0; b < kBins; ++b)
    dat << 1.0 + (b + 0.5) * (top - 1.0) / kBins << ' ' << counts[b][0] << ' ' << counts[b][1] << "\n";
  write_whole(dir + "/global_cost.dat", dat);
  std::ostringstream gp;
  gp << png_output("1000,420", "global_cost.png")
     << "set multiplot layout 1,2 title 'What the 44 candidate directions cost: squared PD_d over the "
     << "minimum over every plane (eq. 5), " << s.pairs << " pairs'\n"
     << "set style fill solid 0.6 border -1\nset boxwidth " << (top - 1.0) / kBins << "\nset xrange [1:"
     << top << "]\nset ylabel '% of pairs'\nset grid ytics\n"
     << std::fixed << std::setprecision(3)
     << "set xlabel 'pdd2\\_relaxed / pdd2\\_global'\nset title 'relaxed, best candidate: mean "
     << s.relaxed_over_global.mean << "'\nplot 'global_cost.dat' using 1:2 with boxes lc rgb '#4477aa' notitle\n"
     << "set xlabel 'pdd2 / pdd2\\_global'\nset title 'paper case 2: mean " << s.pdd2_over_global.mean
     << "'\nplot 'global_cost.dat' using 1:3 with boxes lc rgb '#cc3311' notitle\nunset multiplot\n";
  write_whole(dir + "/global_cost.gp", gp);
  return run_gnuplot(dir, "global_cost.gp", "global_cost.png", why);
}

bool write_fig2(const std::string& dir, const PairConfigurations& c, std::string& why) {
  std::ostringstream dat;
  dat << std::setprecision(17);
  // index 0..7: A rest, B rest, A rest, B static, A def, B def, A rest, B rigid
  const TetVertices* blocks[8] = {&c.A_rest, &c.B_rest, &c.A_rest, &c.B_static,
                                  &c.A_deformable, &c.B_deformable, &c.A_rest, &c.B_rigid};
  for (const auto* t : blocks) {
    write_edges(dat, *t);
    dat << "\n";  // two blank lines end a gnuplot index block
  }
  write_whole(dir + "/fig2_pair.dat", dat);  // gnuplot reads it below
  std::ostringstream titles[4];
  titles[0] << "(a) penetration state";
  titles[1] << std::setprecision(4) << "(b) static / deformable, PD_d = " << c.pdd_static;
  titles[2] << std::setprecision(4) << "(c) deformable / deformable, PD_d = " << c.pdd;
  titles[3] << std::setprecision(4) << "(d) rigid, PD = " << c.pd;
  // One cube around every configuration, the same in all panels.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const auto* t : blocks)
    for (const auto& v : *t)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  double span = 0;
  for (int k = 0; k < 3; ++k) span = std::max(span, hi[k] - lo[k]);
  std::ostringstream gp;
  gp << png_output("1400,1200", "fig2_pair.png", 12)
     << "set multiplot layout 2,2 title 'pair " << c.name << ": A (blue) and B (red), rest pose dashed (cf. paper Fig. 2)'\n"
     << "set view 65,35\nset view equal xyz\nset xyplane 0\nunset key\nset format '%.1f'\n";
  const char axes[3] = {'x', 'y', 'z'};
  for (int k = 0; k < 3; ++k) {
    const double mid = 0.5 * (lo[k] + hi[k]);
    gp << "set " << axes[k] << "range [" << mid - 0.55 * span << ":" << mid + 0.55 * span << "]\n";
  }
  for (int i = 0; i < 4; ++i) {
    gp << "set title '" << titles[i].str() << "'\n"
       << "splot 'fig2_pair.dat' index " << 2 * i << " with lines lw 2 lc rgb '#4477aa', "
       << "'' index " << 2 * i + 1 << " with lines lw 2 lc rgb '#cc3311'";
    if (i > 0)
      gp << ", '' index 0 with lines dt 2 lc rgb '#99bbdd', '' index 1 with lines dt 2 lc rgb '#ee9988'";
    gp << "\n";
  }
  gp << "unset multiplot\n";
  write_whole(dir + "/fig2_pair.gp", gp);
  return run_gnuplot(dir, "fig2_pair.gp", "fig2_pair.png", why);
}

void write_vtk(const std::string& path, const PairConfigurations& c) {
  const TetVertices* cells[6] = {&c.A_rest, &c.B_rest, &c.B_static, &c.A_deformable, &c.B_deformable, &c.B_rigid};
  std::ostringstream o;
  o << std::setprecision(17) << "# vtk DataFile Version 3.0\n"
    << "pdd pair " << c.name << ": 0 A rest, 1 B rest, 2 B static/def, 3 A def/def, 4 B def/def, 5 B rigid\n"
    << "ASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 24 double\n";
  for (const auto* t : cells)
    for (const auto& v : *t) o << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  // VTK_TETRA wants (p1 - p0) . ((p2 - p0) x (p3 - p0)) > 0: each cell takes the vertex order
  // that makes its rest tetrahedron positive (A's for cell 3, B's for 2, 4, 5), so a deformed
  // cell that turned inside out shows as negative. (Doubles: the picture's sign only.)
  auto positive = [](const TetVertices& t) {
    double e[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) e[i][k] = t[i + 1][k] - t[0][k];
    return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]) > 0;
  };
  const bool rest_positive[6] = {positive(c.A_rest), positive(c.B_rest), positive(c.B_rest),
                                 positive(c.A_rest), positive(c.B_rest), positive(c.B_rest)};
  o << "CELLS 6 30\n";
  for (int k = 0; k < 6; ++k) {
    const int second = rest_positive[k] ? 1 : 2, third = rest_positive[k] ? 2 : 1;
    o << "4 " << 4 * k << ' ' << 4 * k + second << ' ' << 4 * k + third << ' ' << 4 * k + 3 << '\n';
  }
  o << "CELL_TYPES 6\n";
  for (int k = 0; k < 6; ++k) o << "10\n";  // VTK_TETRA
  o << "CELL_DATA 6\nSCALARS configuration int 1\nLOOKUP_TABLE default\n0\n1\n2\n3\n4\n5\n";
  write_whole(path, o);
}

}  // namespace pdd::compare
