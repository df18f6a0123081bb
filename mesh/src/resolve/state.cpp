// state.cpp — a mesh's state during a resolve run (state.h).
#include "state.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../check_indices.h"
#include "../element_quality.h"
#include "../resolve.h"

namespace pdd::mesh::detail {

bool Side::any_fixed() const { return std::find(fixed.begin(), fixed.end(), 1) != fixed.end(); }
bool Side::all_fixed() const { return std::find(fixed.begin(), fixed.end(), 0) == fixed.end(); }

void check_fixed_flags(const std::vector<char>& flags, const Mesh& m, char which) {
  if (!flags.empty() && flags.size() != m.vertices.size()) {
    std::ostringstream o;
    o << "fixed-vertex flags of mesh " << which << ": " << flags.size() << " flags for " << m.vertices.size()
      << " vertices";
    throw std::invalid_argument(o.str());
  }
}

namespace {

// The valid elements of each vertex, as CSR (Side::vertex_start, vertex_elems).
void vertex_elements(Side& s, const Mesh& m) {
  s.vertex_start.assign(m.vertices.size() + 1, 0);
  for (std::size_t e : s.elems)
    for (std::size_t v : m.tets[e]) ++s.vertex_start[v + 1];
  for (std::size_t v = 0; v < m.vertices.size(); ++v) s.vertex_start[v + 1] += s.vertex_start[v];
  s.vertex_elems.resize(s.vertex_start.back());
  std::vector<std::size_t> fill(s.vertex_start.begin(), s.vertex_start.end() - 1);
  for (std::size_t e : s.elems)
    for (std::size_t v : m.tets[e]) s.vertex_elems[fill[v]++] = e;
}

}  // namespace

void init_side(Side& s, const Mesh& m, char which, bool fix_all, const std::vector<char>& flags,
               std::vector<SkippedElement>& skipped) {
  check_indices(m, which);
  check_fixed_flags(flags, m, which);
  s.rest = &m;
  s.which = which;
  s.cur = m;
  s.fixed = fix_all ? std::vector<char>(m.vertices.size(), 1)
                    : flags.empty() ? std::vector<char>(m.vertices.size(), 0) : flags;
  s.elems = valid_elements(m, which, &skipped);
  s.sign.assign(m.tets.size(), Sign::Zero);
  s.d0.assign(m.tets.size(), 0);
  s.s0.assign(m.tets.size(), 0);
  s.factor.assign(m.tets.size(), 1);
  s.volume.assign(m.tets.size(), 0);
  tbb::parallel_for(std::size_t{0}, s.elems.size(), [&](std::size_t k) {
    const std::size_t e = s.elems[k];
    const TetVertices t = element(m, e);
    s.sign[e] = orientation(t[0], t[1], t[2], t[3]);
    s.factor[e] = edge_scale(t);
    s.d0[e] = volume6(scaled(t, s.factor[e]));
    s.s0[e] = edge_square_sum(scaled(t, s.factor[e]));
  });
  // The volume weights (step_limit.h's WeightedMean) only as ratios: every element scaled by the
  // side's smallest factor (its largest element's), which keeps them in range at any mesh size.
  double side = s.elems.empty() ? 1 : HUGE_VAL;
  for (std::size_t e : s.elems) side = std::min(side, s.factor[e]);
  for (std::size_t e : s.elems) s.volume[e] = std::abs(volume6(scaled(element(m, e), side))) / 6;
  vertex_elements(s, m);
  s.acc.assign(m.vertices.size(), {0, 0, 0});
  s.weight.assign(m.vertices.size(), 0);
}

double side_cost(const Side& s) { return mesh_cost(*s.rest, s.cur.vertices); }

}  // namespace pdd::mesh::detail
