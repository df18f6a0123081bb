// random.h — pdd's reproducible random numbers: the same sequence with every standard library.
//
// std::mt19937_64's output sequence is fixed by the C++ standard; the distributions of <random>
// (uniform_real_distribution, uniform_int_distribution) are not, and differ between libstdc++
// and libc++. The conversions below use exact bit manipulation and correctly rounded
// arithmetic only, so fixture families and randomised tests draw the same numbers everywhere.
// Header-only (target pdd_random): the fast engine's tests use it without linking anything.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace pdd::compare {

class ReproducibleRng {
 public:
  explicit ReproducibleRng(std::uint64_t seed) : g_(seed) {}
  double uniform01() { return double(g_() >> 11) * 0x1.0p-53; }  // [0, 1), 53 random bits
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  // An integer in [lo, hi] (modulo bias below 2^-40 for the small ranges used here).
  // (The range's size is taken in 64 bits: hi − lo + 1 overflows an int for [0, INT_MAX].)
  int integer(int lo, int hi) {
    return int(lo + std::int64_t(g_() % std::uint64_t(std::int64_t(hi) - lo + 1)));
  }
  // A multiple of `step` (a power of two) in [lo, hi]: exact, few significant bits.
  double grid(double lo, double hi, double step) {
    return lo + step * integer(0, int(std::floor((hi - lo) / step)));
  }

 private:
  std::mt19937_64 g_;
};

}  // namespace pdd::compare
