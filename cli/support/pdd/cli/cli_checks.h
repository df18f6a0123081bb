// cli_checks.h — CLI11 validators for the numbers of `pdd` options.
//
// CLI11 2.1 converts "-1" to 2^64-1 for an unsigned option and accepts "nan" for a double
// option checked with CLI::PositiveNumber; its NonNegativeNumber prints a 309-digit range.
// These validators look at the text before it is converted and say briefly what is wrong;
// a failed check is a usage error (exit 2).
#pragma once

#include <CLI/CLI.hpp>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>

namespace pdd::compare {

// Whether two paths name one file: the same existing file, or the same path once normalised
// (an output that does not exist yet). An output that is also an input would be emptied before
// it is read (`pdd solve --input f --output f` would leave f empty); two outputs
// that are one file would overwrite each other.
inline bool same_file(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return false;
  std::error_code e;
  if (std::filesystem::equivalent(a, b, e)) return true;
  const auto ca = std::filesystem::weakly_canonical(a, e);
  if (e) return false;
  const auto cb = std::filesystem::weakly_canonical(b, e);
  return !e && ca == cb;
}

// A decimal integer in [lo, hi] (no sign unless lo < 0, no spaces, no fraction).
inline CLI::Validator integer_in(long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& s) -> std::string {
        long long v = 0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (s.empty() || end != s.data() + s.size() ||
            (ec != std::errc() && ec != std::errc::result_out_of_range))
          return "'" + s + "' is not an integer";
        if (ec == std::errc::result_out_of_range || v < lo || v > hi)
          return s + " is out of range " + range;
        return {};
      },
      "INT in " + range, "integer_in");
}

// A seed: any unsigned 64-bit integer, written in decimal without a sign.
inline CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        std::uint64_t v = 0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (s.empty() || s[0] == '-' || s[0] == '+' || end != s.data() + s.size())
          return "'" + s + "' is not a seed (an integer from 0 to 2^64-1)";
        if (ec != std::errc()) return s + " is out of range for a seed (0 to 2^64-1)";
        return {};
      },
      "UINT64", "seed_value");
}

inline std::string short_number(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

// A finite number >= lo (strictly > lo when `strict`).
inline CLI::Validator finite_number(double lo, bool strict) {
  return CLI::Validator(
      [lo, strict](std::string& s) -> std::string {
        errno = 0;
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size()) return "'" + s + "' is not a number";
        if (!std::isfinite(v)) return "'" + s + "' is not a finite number";
        if (strict ? !(v > lo) : !(v >= lo))
          return s + " must be " + (strict ? "> " : ">= ") + short_number(lo);
        return {};
      },
      strict ? "NUMBER > " + short_number(lo) : "NUMBER >= " + short_number(lo),
      "finite_number");
}

}  // namespace pdd::compare
