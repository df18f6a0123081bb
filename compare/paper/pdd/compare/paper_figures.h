// paper_figures.h — the pictures of `pdd paper`: the paper's Fig. 3 (histograms of
// PD_d / PD) and Fig. 2 (one pair before and after resolution), drawn by gnuplot from data
// files written here, and a VTK legacy file of the same before/after tetrahedra for ParaView.
#pragma once

#include <string>
#include <vector>

#include "pdd/compare/paper_experiment.h"
#include "pdd/tet_pair.h"

namespace pdd::compare {

// One pair in its resolutions (Fig. 2): rest; case 1 (A static, B deformed); case 2 (both
// deformed); rigid (B translated by PD along the rigid direction). Computed exactly.
struct PairConfigurations {
  std::string name;
  TetVertices A_rest, B_rest, B_static, A_deformable, B_deformable, B_rigid;
  double pd = 0, pdd_static = 0, pdd = 0;  // PD and PD_d (not squared)
};

PairConfigurations pair_configurations(const TetPair& pair);

// The writers below throw std::runtime_error when a file cannot be written in full. Every file
// (data, script, picture, VTK) is written under a temporary name beside it and renamed over it
// when complete: an interrupted or failed run leaves the old file or the whole new one.

// Writes DIR/fig3_histograms.{dat,gp,png}; returns false (with `why`) when gnuplot fails.
bool write_fig3(const std::string& dir, const PaperStats& stats, std::string& why);

// Writes DIR/global_cost.{dat,gp,png}: histograms of pdd2_relaxed / pdd2_global and
// pdd2 / pdd2_global (definitions §9); returns false (with `why`) when gnuplot fails.
bool write_global_figure(const std::string& dir, const GlobalStats& stats, std::string& why);

// Writes DIR/fig2_pair.{dat,gp,png}; returns false (with `why`) when gnuplot fails.
bool write_fig2(const std::string& dir, const PairConfigurations& c, std::string& why);

// Writes DIR/pair_before_after.vtk: six tetra cells (A rest, B rest, B static/def, A def/def,
// B def/def, B rigid) with a cell scalar `configuration` 0..5 in that order.
void write_vtk(const std::string& path, const PairConfigurations& c);

}  // namespace pdd::compare
