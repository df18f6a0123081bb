// qp_formulation.h — the two formulations of the per-direction QP that the reference engine can
// solve (definitions §5). Both give the same exact optimum (tested on every fixture family);
// Reduced has 8 variables instead of 27 and is much faster. Plain data.
//   Full     the paper's variables q1_A, q1_B, p_s (eq. 3 with the constraints of eq. 10);
//   Reduced  the displacement along the direction only (definitions §5's reduction).
#pragma once

namespace pdd {

enum class QpFormulation { Full, Reduced };

inline const char* to_string(QpFormulation f) { return f == QpFormulation::Full ? "full" : "reduced"; }

}  // namespace pdd
