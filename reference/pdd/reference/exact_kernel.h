// exact_kernel.h — the number types of the exact engine: the one place they are decided.
//
// Rational  GMP rational (CGAL::Gmpq). Every input double is taken as the rational it denotes
//           (definitions §1); every construction (cross products, dot products, squared lengths,
//           QP optima) stays exact.
// Kernel    CGAL Cartesian kernel over Rational: predicates and constructions exact.
// QpNumber  CGAL::Gmpzf, arbitrary-precision dyadic floats, the type CGAL's QP solver is
//           fastest with. Every QP coefficient we build is a polynomial in input doubles,
//           hence dyadic, hence represented exactly (to_qp_number checks it).
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpzf.h>
#include <CGAL/Simple_cartesian.h>

#include <array>
#include <string>

#include "pdd/tet_pair.h"

namespace pdd::reference {

using Rational = CGAL::Gmpq;
using Kernel = CGAL::Simple_cartesian<Rational>;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using QpNumber = CGAL::Gmpzf;

using ExactTet = std::array<Point, 4>;

// The pair of definitions §1 with every coordinate converted exactly.
struct ExactPair {
  ExactTet A;  // s0..s3
  ExactTet B;  // r0..r3
};

// Exact conversion of finite doubles (the caller validates finiteness first).
ExactTet to_exact(const TetVertices& tet);
ExactPair to_exact(const TetPair& pair);

// "p/q" in lowest terms, or "p" for an integer (definitions §6).
std::string to_string(const Rational& q);

// Exact conversions between the geometry and QP number types. to_qp_number throws
// std::logic_error when q is not dyadic (which would be a bug in the caller).
QpNumber to_qp_number(const Rational& q);
Rational to_rational(const QpNumber& x);

}  // namespace pdd::reference
