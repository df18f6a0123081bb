#include "pdd/reference/candidate_table.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "pdd/reference/oriented_depth.h"

namespace pdd::reference {

namespace {

CandidateRow row_of(const ExactPair& pair, const CandidateDirection& dir, QpFormulation f) {
  const Rational D = oriented_depth_numerator(pair, dir.n);
  CandidateRow row{dir, D, D * CGAL::abs(D) / dir.n.squared_length(), std::nullopt, {}, {}};  // = oriented_depth_signed_square
  row.static_case = direction_qp(pair, dir, PddCase::Static, f);
  auto deformable = direction_qp(pair, dir, PddCase::Deformable, f);
  auto relaxed = direction_qp(pair, dir, PddCase::Relaxed, f);
  if (!deformable || !relaxed)  // case 2 is always feasible: move everything onto a plane
    throw std::logic_error("candidate_table: case-2 QP infeasible on " + dir.label.str());
  row.deformable = std::move(*deformable);
  row.relaxed = std::move(*relaxed);
  return row;
}

}  // namespace

std::vector<CandidateRow> candidate_table(const ExactPair& pair,
                                          const std::vector<CandidateDirection>& candidates,
                                          const CandidateTableOptions& options) {
  std::vector<CandidateRow> rows;
  rows.reserve(candidates.size());
  for (const CandidateDirection& dir : candidates) rows.push_back(row_of(pair, dir, options.formulation));
  return rows;
}

std::optional<CandidateRow> candidate_row(const ExactPair& pair, const DirectionLabel& label,
                                          const CandidateTableOptions& options) {
  for (const CandidateDirection& dir : candidate_directions(pair))
    if (dir.label == label) return row_of(pair, dir, options.formulation);
  return std::nullopt;
}

std::vector<std::size_t> depth_order(const std::vector<CandidateRow>& rows) {
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return rows[a].depth_signed_square < rows[b].depth_signed_square;
  });
  return order;
}

}  // namespace pdd::reference
