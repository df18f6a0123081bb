// summary_text.h — the layout of the summaries `pdd` prints for people (`pdd resolve --summary`,
// `pdd mesh --summary`): a headline, then one line per item with its label in a column of
// kSummaryLabel characters, tables right-aligned under it; numbers with 6 significant digits
// (the JSON outputs keep every digit).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>

namespace pdd::io {

// Width of the label column.
inline constexpr std::size_t kSummaryLabel = 18;

// 6 significant digits, %g style.
inline std::string summary_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// A resolution's cost: summary_number, or "not representable" where the JSON report has null (a
// cost outside the double range, mesh_cost's +inf or NaN).
inline std::string summary_cost(double x) {
  return std::isfinite(x) ? summary_number(x) : "not representable";
}

// "  label             text\n" (text's later lines, if any, indented to the text column).
inline std::string summary_line(const std::string& label, const std::string& text) {
  std::string out = "  " + label;
  out += std::string(label.size() < kSummaryLabel ? kSummaryLabel - label.size() : 1, ' ');
  for (char c : text) {
    out += c;
    if (c == '\n') out += std::string(2 + kSummaryLabel, ' ');
  }
  return out + '\n';
}

// "1 tetrahedron", "n tetrahedra".
inline std::string tetrahedra(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " tetrahedron" : " tetrahedra");
}

// `s` right-aligned in `width` characters (a table cell).
inline std::string padded_left(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

}  // namespace pdd::io
