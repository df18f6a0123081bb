// hot_path.h — internal to fast/src: the definitions §8 frame of the functions over raw tetrahedra
// (rigid_pd2(A, B), pdd2_static(A, B), ...): power-of-two rescaling (power_scale.h), the double
// path when its choice is certified (value_bounds.h), else the exact path (exact_path.h).
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "exact/exact_path.h"
#include "exact/exact_predicates.h"
#include "kernel/direction_geometry.h"
#include "kernel/power_scale.h"
#include "kernel/rigid_depth.h"

namespace pdd::fast::detail {

// The value and label that the exact path gives for one quantity; value 0 (index −1, not
// certified... but exact) for a non-intersecting or invalid pair, NaN when not representable.
template <class Pick>
Choice exact_choice(const TetVertices& A, const TetVertices& B, Pick pick) {
  if (!all_finite(A) || !all_finite(B) || orientation_sign_exact(A) == Sign::Zero ||
      orientation_sign_exact(B) == Sign::Zero)
    return {};
  const ExactPathResult e = solve_pair_exact_path(A, B);
  Choice ch;
  ch.certified = true;
  if (!e.result.intersecting) return ch;
  if (!e.representable) {
    ch.value = std::numeric_limits<double>::quiet_NaN();
    ch.certified = false;
    return ch;
  }
  std::optional<DirectionLabel> label;
  ch.value = pick(e.result, label);
  if (label) ch.code = pack_label(label->kind, label->a, label->b, label->orientation);
  return ch;
}

// `run(As, Bs, ch)`: the double path on the rescaled pair; returns false when the pair is
// invalid or does not intersect (value 0). Its choice is used when certified.
template <class Run, class Pick>
Choice certified_hot_path(const TetVertices& A, const TetVertices& B, Run run, Pick pick) {
  const ScaledPair sp = power_scaled(A, B);
  if (!sp.finite) return {};
  if (sp.exact) {
    Choice ch;
    if (!run(sp.A, sp.B, ch)) return {};
    if (ch.certified) {
      bool ok = true;
      ch.value = unscaled(ch.value, -2 * sp.e, ok);
      if (ok) return ch;
      ch.value = std::numeric_limits<double>::quiet_NaN();
      ch.certified = false;
      return ch;
    }
  }
  return exact_choice(A, B, pick);
}

// certified_hot_path with a first try that fuses the rescaling into the kernel
// (superset_kernel_scaled): `fused(ch, e)` returns true with a choice on the pair rescaled by
// 2^e when power_scale.h's common exact case applies; a certified one whose value scales back
// into the normal range is what certified_hot_path would return (the same scaled pair, the
// same double path: each caller argues that its `fused` is its `run` on it). Everything else
// goes the general way (recomputing: rare).
template <class Fused, class Run, class Pick>
Choice fused_hot_path(const TetVertices& A, const TetVertices& B, Fused fused, Run run, Pick pick) {
  {
    Choice ch;
    int e = 0;
    if (fused(ch, e) && ch.certified) {
      bool ok = true;
      ch.value = unscaled(ch.value, -2 * e, ok);
      if (ok) return ch;
    }
  }
  return certified_hot_path(A, B, run, pick);
}

}  // namespace pdd::fast::detail
