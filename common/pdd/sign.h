// sign.h — the sign of an exactly decided quantity (an orientation, a depth), as CGAL's
// Orientation / Sign name it: never a bare int. Plain data.
#pragma once

namespace pdd {

enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

// The sign of an integer-valued sign test (any negative, zero or positive int).
constexpr Sign sign_of(int s) { return s > 0 ? Sign::Positive : (s < 0 ? Sign::Negative : Sign::Zero); }

// ±1 (0 for Zero), for formulas that multiply by a sign.
constexpr int to_int(Sign s) { return static_cast<int>(s); }

}  // namespace pdd
