#include "pdd/reference/relaxed_pieces.h"

#include <stdexcept>

namespace pdd::reference {
namespace {

Vector position(const Point& p) { return p - CGAL::ORIGIN; }

int count(unsigned mask) { return __builtin_popcount(mask & 15u); }

void add_outer(std::array<std::array<Rational, 3>, 3>& H, const Vector& v) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H[r][c] += v[r] * v[c];
}

}  // namespace

RelaxedPiece relaxed_piece(const ExactPair& pair, ActiveSet set) {
  const int mA = count(set.a), mB = count(set.b);
  if (mA == 0 || mB == 0) throw std::invalid_argument("relaxed_piece: a side has no active vertex");
  RelaxedPiece p;
  p.set = set;
  Vector sum_A = CGAL::NULL_VECTOR, sum_B = CGAL::NULL_VECTOR;
  for (int i = 0; i < 4; ++i) {
    if (set.a >> i & 1u) sum_A = sum_A + position(pair.A[i]);
    if (set.b >> i & 1u) sum_B = sum_B + position(pair.B[i]);
  }
  const Rational wA = Rational(1) / (5 - mA), wB = Rational(1) / (5 - mB);
  p.C = (sum_A * wA + sum_B * wB) / (wA * mA + wB * mB);   // c = C.n
  const Vector TA = (p.C * Rational(mA) - sum_A) * wA;      // T_A = TA.n
  const Vector TB = -TA;                                    // T_A + T_B = 0
  for (auto& row : p.H) row.fill(Rational(0));
  for (int i = 0; i < 4; ++i) {
    const Vector s = position(pair.A[i]), r = position(pair.B[i]);
    p.t_A[i] = (set.a >> i & 1u) ? p.C - s : -TA;
    p.t_B[i] = (set.b >> i & 1u) ? p.C - r : -TB;
    p.D[i] = s - p.C - TA;  // d_i = a_i - c - T_A
    p.E[i] = p.C - r + TB;  // e_j = c - b_j + T_B
    add_outer(p.H, p.t_A[i]);
    add_outer(p.H, p.t_B[i]);
  }
  add_outer(p.H, TA);
  add_outer(p.H, TB);
  for (auto& row : p.H)
    for (Rational& h : row) h /= 20;
  return p;
}

bool piece_is_optimal_at(const RelaxedPiece& piece, const Vector& n) {
  for (int i = 0; i < 4; ++i) {
    const CGAL::Sign d = CGAL::sign(piece.D[i] * n), e = CGAL::sign(piece.E[i] * n);
    if ((piece.set.a >> i & 1u) ? d == CGAL::NEGATIVE : d == CGAL::POSITIVE) return false;
    if ((piece.set.b >> i & 1u) ? e == CGAL::NEGATIVE : e == CGAL::POSITIVE) return false;
  }
  return true;
}

Rational piece_quadratic(const RelaxedPiece& piece, const Vector& n) {
  Rational q = 0;
  for (int r = 0; r < 3; ++r) {
    Rational row = 0;
    for (int c = 0; c < 3; ++c) row += piece.H[r][c] * n[c];
    q += row * n[r];
  }
  return q;
}

void piece_positions(const ExactPair& pair, const RelaxedPiece& piece, const Vector& n,
                     ExactTet& q1_A, ExactTet& q1_B) {
  const Rational nn = n.squared_length();
  for (int i = 0; i < 4; ++i) {
    q1_A[i] = pair.A[i] + n * ((piece.t_A[i] * n) / nn);
    q1_B[i] = pair.B[i] + n * ((piece.t_B[i] * n) / nn);
  }
}

std::optional<DualCertificate> dual_certificate(const ExactPair& pair, const RelaxedPiece& piece,
                                                const Vector& n) {
  std::array<Rational, 4> lA, lB;
  Rational sumA = 0, sumB = 0;
  for (int i = 0; i < 4; ++i) {
    lA[i] = (piece.set.a >> i & 1u) ? Rational(piece.D[i] * n) / 10 : Rational(0);
    lB[i] = (piece.set.b >> i & 1u) ? Rational(piece.E[i] * n) / 10 : Rational(0);
    if (lA[i] < 0) lA[i] = 0;
    if (lB[i] < 0) lB[i] = 0;
    sumA += lA[i], sumB += lB[i];
  }
  if (sumA == 0 || sumB == 0) return std::nullopt;
  if (sumA != sumB) {  // scale the heavier side down: still >= 0, now balanced
    if (sumA > sumB) {
      const Rational f = sumB / sumA;
      for (Rational& l : lA) l *= f;
      sumA = sumB;
    } else {
      const Rational f = sumA / sumB;
      for (Rational& l : lB) l *= f;
      sumB = sumA;
    }
  }
  DualCertificate cert{CGAL::NULL_VECTOR, 0};
  Rational nA = 0, nB = 0;
  for (int i = 0; i < 4; ++i) {
    cert.g = cert.g + position(pair.A[i]) * lA[i] - position(pair.B[i]) * lB[i];
    nA += lA[i] * lA[i], nB += lB[i] * lB[i];
  }
  cert.K = 5 * nA - sumA * sumA + 5 * nB - sumB * sumB;
  return cert;
}

}  // namespace pdd::reference
