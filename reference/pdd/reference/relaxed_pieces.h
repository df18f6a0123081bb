// relaxed_pieces.h — the relaxed QP of definitions §5 along ANY normal n (definitions §9), in
// closed form per active set, and the dual bound that certifies a lower bound of it on a whole cone
// of normals.
//
// Input : an exact pair (A = s0..s3, B = r0..r3), an active set, normals n (exact vectors).
// Output: the piece of G on which that active set is optimal: G(n) = n^T H n there, the
//         deformed positions, the exact test "is this active set optimal at n", and dual
//         certificates (g, K) with G(n) >= g.n - K for EVERY n.
//
// The function. For n != 0 let a_i = n.s_i, b_j = n.r_j and
//   G(n) = min over t_A, t_B in R^4, c in R of  t_A^T M t_A + t_B^T M t_B,   M = (I + J) / 20,
//          subject to  a_i + t_i <= c  (every vertex of A),   b_j + t_j >= c  (every vertex of B).
// A vertex x displaced by t along a unit vector u has sigma = t^T M t (definitions §2), so for |u|
// = 1 G(u) is the relaxed QP of definitions §5 with normal u and no constrained vertex: the
// quantity whose minimum over the unit sphere is pdd2_global (definitions §9). The right-hand sides
// are linear in n, so G(s n) = s^2 G(n) for s > 0 (substitute t = s t', c = s c'), and G(n)/|n|^2 =
// G(n/|n|).
//
// Convexity (definitions §9 asks for the proof). Write the QP as min Q(z) s.t. E z <= F n with z =
// (t_A, t_B, c), Q convex. For n1, n2 with optima z1, z2 and 0 <= w <= 1, z = w z1 + (1-w) z2
// satisfies E z <= F (w n1 + (1-w) n2) and Q(z) <= w Q(z1) + (1-w) Q(z2): G is convex on R^3.
//
// Duality (what certifies lower bounds). For multipliers l_A, l_B >= 0 with
// sum l_A = sum l_B (the condition that makes the Lagrangian bounded in c), weak duality gives,
// for EVERY n,
//   G(n) >= min_t [t_A^T M t_A + l_A.t_A + t_B^T M t_B - l_B.t_B] + sum_i l_i a_i - sum_j l_j b_j
//         = g.n - K,   g = sum_i l_i s_i - sum_j l_j r_j,
//   K = (l_A^T M^-1 l_A + l_B^T M^-1 l_B) / 4 = 5|l_A|^2 - (sum l_A)^2 + 5|l_B|^2 - (sum l_B)^2
// (M^-1 = 20 (I - J/5), since (I + J)(I - J/5) = I for 4x4 J). Scaling l by s > 0 keeps it
// admissible, and max over s of (s g.n - s^2 K) = (g.n)^2 / (4K) when g.n >= 0 (K > 0 when l != 0:
// (sum l)^2 <= 4|l|^2 < 5|l|^2). Hence, for unit u with g.u >= 0:
//   relaxed(u) = G(u) >= (g.u)^2 / (4 K).                                              (D)
// With l the optimal multipliers at u0, (D) is tight at u0 (strong duality: G(u0) = g.u0 - K
// and, l being optimal, s = 1 maximises, so g.u0 = 2K and G(u0) = K = (g.u0)^2 / (4K)).
//
// Active sets (the closed form). Lagrangian L = Q + sum l_i (a_i + t_i - c) + sum l_j (c - b_j - t_j).
// Stationarity in t: 2 (M t_A)_i + l_i = 0, i.e. l_i = -(t_i + T_A) / 10 with T_A = sum t_A;
// 2 (M t_B)_j - l_j = 0, i.e. l_j = (t_j + T_B) / 10; in c: sum l_A = sum l_B.
// A vertex of A is active (t_i = c - a_i) or free (l_i = 0, so t_i = -T_A). With
//   d_i = a_i - c - T_A:  active needs l_i = d_i / 10 >= 0, free needs t_i <= c - a_i, i.e.
//   d_i <= 0: the active set is the vertices of A above the threshold c + T_A. Likewise for B
//   with e_j = c - b_j + T_B: active needs e_j >= 0 (l_j = e_j / 10), free needs e_j <= 0.
// Summing t over A with m_A = |S_A| active vertices: T_A = (m_A c - sum_{S_A} a_i) / (5 - m_A),
// and sum l_A = -T_A / 2; over B: T_B = (m_B c - sum_{S_B} b_j) / (5 - m_B), sum l_B = T_B / 2.
// The c-condition is T_A + T_B = 0, so with w = 1 / (5 - m)
//   c = (w_A sum_{S_A} a_i + w_B sum_{S_B} b_j) / (m_A w_A + m_B w_B).
// Every quantity is linear in n: c = C.n, T_A = TA.n, t_i = t_i.n, d_i = D_i.n, e_j = E_j.n,
// and G(n) = sum_T (|t_T|^2 + T_T^2) / 20 = n^T H n. The KKT conditions of the set are the
// linear sign conditions on D_i.n and E_j.n, so the set of n where an active set is optimal
// is a closed polyhedral cone: a conic combination of normals where it is optimal keeps it
// optimal. An intersecting pair has G(n) > 0 for all n; then both sides have an active vertex
// (S_A empty forces T_A = 0, hence sum l_B = 0, hence nobody moves and G(n) = 0), so only the
// 15 x 15 sets with both sides non-empty occur.
//
// Everything here is exact (Rational); the caller chooses active sets by any heuristic and the
// sign conditions decide exactly whether a piece applies.
#pragma once

#include <array>
#include <optional>

#include "pdd/reference/exact_kernel.h"

namespace pdd::reference {

// Bit i of `a`: s_i active; bit j of `b`: r_j active. Both non-empty for a piece.
struct ActiveSet {
  unsigned a = 0, b = 0;
  bool operator<(const ActiveSet& o) const { return a != o.a ? a < o.a : b < o.b; }
};

struct RelaxedPiece {
  ActiveSet set;
  Vector C;                            // plane offset c(n) = C.n
  std::array<Vector, 4> t_A, t_B;      // displacement of each vertex along n: t.n (times |n|)
  std::array<Vector, 4> D, E;          // sign conditions: D_i.n (A), E_j.n (B)
  std::array<std::array<Rational, 3>, 3> H;  // G(n) = n^T H n where the set is optimal
};

// The closed form above for one active set (both sides non-empty; std::invalid_argument else).
RelaxedPiece relaxed_piece(const ExactPair& pair, ActiveSet set);

// Exact: the set's KKT conditions hold at n (so G(n) = n^T H n and the positions are optimal).
bool piece_is_optimal_at(const RelaxedPiece& piece, const Vector& n);

// n^T H n (equals G(n) where piece_is_optimal_at(n)).
Rational piece_quadratic(const RelaxedPiece& piece, const Vector& n);

// The deformed positions for normal n: x + (t.n / n.n) n per vertex.
void piece_positions(const ExactPair& pair, const RelaxedPiece& piece, const Vector& n,
                     ExactTet& q1_A, ExactTet& q1_B);

// A dual certificate of (D): g and K from the piece's multipliers at n (l_i = D_i.n / 10 on
// active vertices of A, E_j.n / 10 on B, 0 elsewhere), negative ones set to 0 and the heavier
// side scaled down so that sum l_A = sum l_B (both keep the certificate admissible, whatever
// n and the piece are). nullopt when a side's multipliers are all 0 (no bound).
struct DualCertificate {
  Vector g;
  Rational K;  // > 0
};
std::optional<DualCertificate> dual_certificate(const ExactPair& pair, const RelaxedPiece& piece,
                                                const Vector& n);

}  // namespace pdd::reference
