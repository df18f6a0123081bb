// direction_qp.h — the per-direction QP of definitions §5 (paper eq. 10) in closed form.
//
// Inputs:  for one oriented candidate n, each tetrahedron as a SideProblem: heights H_i = n.x_i
//          (n unnormalised, any common origin) of its constrained vertices (all at one height
//          hcon) and of its free vertices. A is the "below" side, B the "above" side.
// Outputs: DirectionSolution with cost F = sum over both tets of (sum_i T_i² + (sum_i T_i)²),
//          where T_i = displacement along n in the same n-scaled units, the plane offset c and
//          the displacement sums S_A, S_B. The defined value is PD_d²(n) = F / (20 n.n), and the
//          deformed vertex is x_i + (T_i / n.n) n.
//
// ---- Reduction (definitions §5 "facts"). sigma = (1/20)(sum |d_i|² + |sum d_i|²) is a sum over
// the three coordinates of an orthonormal frame (u = n/|n|, u⊥1, u⊥2); the constraints only involve
// the u-components. The orthogonal components thus enter the cost alone and are optimally 0.
// Writing t_i = u.d_i and scaling by |n| (T = |n| t, H = |n| h, C = |n| c) gives, per direction,
//     min  sum_tets (1/20) (sum_i t_i² + (sum_i t_i)²)              [= F / (20 n.n)]
//     s.t. A:  H_i + T_i = C (i in C_A),  H_i + T_i <= C (i in F_A)
//          B:  H_j + T_j = C (j in C_B),  H_j + T_j >= C (j in F_B).
// The Hessian of sum t² + (sum t)² is 2(I + J), positive definite: the problem is strictly
// convex in T, the constraints are linear, so KKT is necessary and sufficient and T is unique.
//
// ---- KKT. L = F + sum_A l_i (H_i + T_i − C) + sum_B m_j (C − H_j − T_j), l, m >= 0 on free
// vertices (sign-free on constrained ones), complementary slackness.
//   dL/dT_i = 2 T_i + 2 S_A + l_i = 0   =>  l_i = −2 (T_i + S_A)          (A)
//   dL/dT_j = 2 T_j + 2 S_B − m_j = 0   =>  m_j =  2 (T_j + S_B)          (B)
//   dL/dC   = −sum l + sum m = 0         =>  10 S_A + 10 S_B = 0          (plane balance)
// For fixed C the two tetrahedra decouple. On side A a free vertex is either active (T_i = C −
// H_i, needs l_i >= 0: C − H_i <= −S_A) or inactive (l_i = 0: T_i = −S_A <= C − H_i), i.e.
//     T_i = min(C − H_i, −S_A),   and on B   T_j = max(C − H_j, −S_B).
// The test "H_i >= C + S_A" has one threshold, so the active free vertices of A are the k
// highest, those of B the k lowest ("top-k" structure). With m vertices at the plane (constrained
// or active) of total height P, summing T gives S = sum_active (C − H) − (4 − m) S, so
//     S(C) = (m C − P) / (5 − m),    side cost  = sum_active (C − H)² + (5 − m) S².
// ---- Breakpoints. With m, P the current active set of A, its lowest active free vertex f turns
// inactive when C − f = −S_A, i.e. at 5C = X = (5 − m) f + P. Successive X increase: after
// removing f the next one f' >= f gives X' − X = (6 − m)(f' − f) >= 0. Symmetrically B's lowest
// inactive free vertex g turns active at 5C = (5 − m) g + P and those X increase
// ((4 − m)(g' − g) >= 0). So S_A(C) (resp. S_B) is continuous, piecewise linear, nondecreasing
// (it is dphi/dC / 10 of the convex side cost phi, by the envelope theorem and (A)).
// ---- Algorithm (case 2). G(C) = S_A(C) + S_B(C) is continuous and nondecreasing; at C -> −inf
// all of A is at the plane (S_A slope 4 > 0) and G -> −inf, at +inf all of B is and G -> +inf.
// Walk the merged breakpoints in increasing X, starting from (all A free active, no B free
// active); stop at the first X with G(X/5) >= 0 — sign tested without division as
// 25 (5−mA)(5−mB) G = (mA X − 5 PA)(5 − mB) + (mB X − 5 PB)(5 − mA). The root lies in the current
// region, where G is linear:  C = (PA (5−mB) + PB (5−mA)) / (mA (5−mB) + mB (5−mA)).
// That C with the region's active sets satisfies every KKT condition above, hence is optimal.
// The denominator is 0 only when mA = mB = 0, i.e. nothing needs to move (cost 0).
// Case 1 (A static): S_A is not a variable; A only requires C >= max_i H_i (all of A on its
// side), with equality when C_A is nonempty. Then C = hcon_A (FV, EE), or for C_A empty (VF)
// C = max(max_i H_i, root of S_B), by convexity of phi_B (phi_B' = 10 S_B).
// Relaxed: every vertex of A is "free below", every vertex of B "free above".
#pragma once

namespace pdd::fast {

// One tetrahedron's side of the problem, and the optimum; T = double here, GMP rationals on the
// exact path (direction_qp_impl.h is the algorithm for any ordered field T).
template <class T>
struct Side {
  int ncon = 0;     // number of constrained vertices
  T hcon{};         // their common height
  int nfree = 0;    // number of free vertices
  T hfree[4]{};     // their heights, any order
};
template <class T>
struct Solution {
  T cost{};  // F (see above); PD_d² = cost / (20 n.n)
  T c{};     // plane offset C
  T sumA{};  // S_A (0 in case 1)
  T sumB{};  // S_B
};
using SideProblem = Side<double>;
using DirectionSolution = Solution<double>;

// The side of one tetrahedron for a candidate: heights h, bit i of `constrained` set for the
// constrained vertices (which share one height).
template <class T>
Side<T> side_of(const T h[4], unsigned constrained) {
  Side<T> s;
  for (int i = 0; i < 4; ++i) {
    if (constrained >> i & 1u) {
      ++s.ncon;
      s.hcon = h[i];
    } else {
      s.hfree[s.nfree++] = h[i];
    }
  }
  return s;
}

// Case 2 (both deform). Requires A.ncon + B.ncon >= 1 or overlapping sides.
DirectionSolution solve_deformable(const SideProblem& A, const SideProblem& B);

// Case 1 (A static). Precondition: feasible, i.e. when A.ncon > 0 no free A vertex is above
// hcon (definitions §5: only undecidable EE directions are infeasible; the caller skips those).
DirectionSolution solve_static(const SideProblem& A, const SideProblem& B);

// Relaxed case 2: hA, hB the four heights of each tetrahedron, every constraint an inequality.
DirectionSolution solve_relaxed(const double hA[4], const double hB[4]);

// Optimal displacement T of one vertex of height h (KKT formulas above).
template <class T>
T displacement_below(const T& h, bool constrained, const Solution<T>& s) {
  const T to_plane = s.c - h;
  return (constrained || to_plane < -s.sumA) ? to_plane : T(-s.sumA);
}
template <class T>
T displacement_above(const T& h, bool constrained, const Solution<T>& s) {
  const T to_plane = s.c - h;
  return (constrained || to_plane > -s.sumB) ? to_plane : T(-s.sumB);
}

}  // namespace pdd::fast
