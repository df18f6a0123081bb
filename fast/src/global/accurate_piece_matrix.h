// accurate_piece_matrix.h — internal to fast/src/global: one piece's matrix H_S (piece
// enumeration, global_depth.h) in double-word arithmetic, with an entrywise error near the
// rounding of its own entries, for the pieces whose double H is too coarse.
//
// Input:  the enumeration's centred vertices pA, pB (doubles) and an active set S = (S_A, S_B)
//         (bit masks ma, mb, both non-empty).
// Output: H, the exact H_S of those vertices rounded entrywise, and h_error >= every entry's
//         absolute error; false when not finite.
//
// Why: the double build's entrywise error bound is 2^-39 of the moments' magnitude (piece_screen.h,
// n_error: ~1.8e-12 L^2), so consider_piece's accuracy estimate 2 E^2 / gap <= 1e-11 mu fails
// for every eigenvalue mu below ~1e-12 L^2: a contact shallower than ~1e-6 of the pair's size
// went to the exact pieces (~5-30 ms a pair). Here E is ~u |H|: the estimate holds down to mu ~
// 1e-19 L^2.
//
// Equation (piece_enumeration.cpp's build, multiplied out so that every coefficient is an
// integer): with m_A = |S_A|, m_B = |S_B|, g = 5 − m_A, the sums S_X = sum of the active
// vertices, Q_X = sum of their outer products, S = S_A + S_B, m = m_A + m_B, k = 10 − m,
//     C = Cn / d,  Cn = (5 − m_B) S_A + (5 − m_A) S_B,  d = m_A (5 − m_B) + m_B (5 − m_A),
//     T_A = U / (d g),  U = m_A Cn − d S_A,
//     20 H D = D (Q_A + Q_B) − d g^2 (Cn S^T + S Cn^T) + m g^2 Cn Cn^T + k U U^T,  D = d^2 g^2,
// the closed form 20 H = Q_A + Q_B − C S^T − S C^T + m C C^T + k T_A T_A^T of
// relaxed_pieces.h (C = (S_A w_A + S_B w_B) / (m_A w_A + m_B w_B), w = 1 / (5 − m),
// T_A = (m_A C − S_A) w_A). d <= 17, D <= 17^2 4^2: every coefficient is an exact double.
#pragma once

#include <Eigen/Core>

#include <array>

#include "certification/double_word.h"

namespace pdd::fast::global {

// The 16 subsets' sums S_X and second moments Q_X (xx xy xz yy yz zz) of A's and B's vertices
// as double words (double_word.h), built once per pair (on the first piece that needs them),
// then each piece's H from them.
class AccurateMoments {
 public:
  AccurateMoments(const std::array<std::array<double, 3>, 4>& pA, const std::array<std::array<double, 3>, 4>& pB);
  // H_S of active set (ma, mb) (both non-empty) rounded entrywise, h_error >= every entry's
  // absolute error; false when not finite.
  bool matrix(unsigned ma, unsigned mb, Eigen::Matrix3d& H, double& h_error) const;
  // The same H_S as double words, each entry with its own certified bound (Bounded: |v - H*| <=
  // e, double_word.h): the entries before their rounding to doubles. False when not finite.
  bool matrix(unsigned ma, unsigned mb, detail::dw::Bounded (&H)[3][3]) const;
  // The vertices H_S is built from (A's, or B's).
  const std::array<std::array<double, 3>, 4>& vertices(bool a) const { return a ? pA_ : pB_; }

 private:
  void fill(const std::array<std::array<double, 3>, 4>& pA, const std::array<std::array<double, 3>, 4>& pB);
  // M = 20 H D's six entries (xx xy xz yy yz zz) as double words, the same expressions on the
  // magnitudes (aM), and 20 D; false for an empty side.
  bool scaled(unsigned ma, unsigned mb, detail::dw::DW (&M)[6], double (&aM)[6], double& c20) const;
  // Each sum as a double word, and the same sum of the terms' magnitudes (|a_k|, |a_r a_c|).
  detail::dw::DW SA[16][3], SB[16][3], QA[16][6], QB[16][6];
  double aSA[16][3], aSB[16][3], aQA[16][6], aQB[16][6];
  std::array<std::array<double, 3>, 4> pA_, pB_;
};

}  // namespace pdd::fast::global
