#include "pdd/io/record_text.h"

#include <gmpxx.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include "pdd/pair_result.h"
#include "pdd/printable.h"

namespace pdd::io {
namespace {

mpz_class pow10(long k) {
  mpz_class r;
  mpz_ui_pow_ui(r.get_mpz_t(), 10, static_cast<unsigned long>(k));
  return r;
}

// 17 significant digits d (a 17-digit integer) times 10^(e - 16), as %.17g would print it:
// positional for -5 <= e < 17, else scientific; trailing zeros dropped.
std::string layout(std::string d, long e, bool negative) {
  while (d.size() > 1 && d.back() == '0') d.pop_back();
  std::string out = negative ? "-" : "";
  if (e >= -5 && e < 17) {
    if (e < 0) return out + "0." + std::string(static_cast<std::size_t>(-e - 1), '0') + d;
    const auto whole = static_cast<std::size_t>(e + 1);
    if (d.size() <= whole) return out + d + std::string(whole - d.size(), '0');
    return out + d.substr(0, whole) + "." + d.substr(whole);
  }
  char exp[32];
  std::snprintf(exp, sizeof exp, "e%c%02ld", e < 0 ? '-' : '+', std::labs(e));
  return out + d.substr(0, 1) + (d.size() > 1 ? "." + d.substr(1) : "") + exp;
}

constexpr std::size_t kNameWidth = 24, kValueWidth = 25, kLabelWidth = 9;

std::string cell(const Json& v, RecordFormat format) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number()) return v.dump();  // the shortest decimal that reads back to the same double
  const std::string s = v.get<std::string>();
  bool exact = true;
  const std::string d = decimal17(s, &exact);
  return (format == RecordFormat::Table && !exact) ? "~" + d : d;
}

std::string csv_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string padded(std::string s, std::size_t width) {
  if (s.size() > width) s = s.substr(0, width - 3) + "...";
  return s + std::string(width + 1 - s.size(), ' ');
}

// The columns, in order: (key, width).
std::vector<std::pair<std::string, std::size_t>> columns() {
  std::vector<std::pair<std::string, std::size_t>> out = {{"name", kNameWidth}, {"intersecting", 12}};
  for (const char* k : kValueKeys) out.emplace_back(k, kValueWidth);
  out.emplace_back("pdd2_global", kValueWidth);
  for (const char* k : kLabelKeys) out.emplace_back(k, kLabelWidth + 7);
  out.emplace_back("error", 0);
  return out;
}

}  // namespace

std::string decimal17(const std::string& rational, bool* exact) {
  mpq_class q(rational);
  q.canonicalize();
  if (exact) *exact = true;
  if (q == 0) return "0";
  const bool negative = q < 0;
  if (negative) q = -q;
  const mpz_class num = q.get_num(), den = q.get_den();
  // e = floor(log10 q): 10^e <= q < 10^(e + 1), from the digit counts (within 2), then exactly
  long e = static_cast<long>(mpz_sizeinbase(num.get_mpz_t(), 10)) -
           static_cast<long>(mpz_sizeinbase(den.get_mpz_t(), 10));
  auto below_pow = [&](long k) {  // q < 10^k
    return k >= 0 ? num < den * pow10(k) : num * pow10(-k) < den;
  };
  while (below_pow(e)) --e;
  while (!below_pow(e + 1)) ++e;
  // n = q 10^(16 - e) rounded half to even: 10^16 <= n <= 10^17
  mpz_class a = num, b = den, n, r;
  if (16 - e >= 0) a *= pow10(16 - e);
  else b *= pow10(e - 16);
  mpz_fdiv_qr(n.get_mpz_t(), r.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
  if (exact) *exact = r == 0;
  const int half = cmp(mpz_class(2 * r), b);
  if (half > 0 || (half == 0 && mpz_odd_p(n.get_mpz_t()))) ++n;
  if (n == pow10(17)) n = pow10(16), ++e;
  return layout(n.get_str(), e, negative);
}

std::string record_header(RecordFormat format) {
  std::string out;
  for (const auto& [key, width] : columns()) {
    if (format == RecordFormat::Csv) out += (out.empty() ? "" : ",") + key;
    else out += width ? padded(key, width) : key;
  }
  return out;
}

std::string record_row(const Json& record, RecordFormat format) {
  if (format == RecordFormat::Jsonl) return record.dump();
  std::string out;
  bool first = true;
  for (const auto& [key, width] : columns()) {
    std::string text;
    if (key == "error") {
      for (const char* k : {"error", "pdd2_global_error"})
        if (record.contains(k) && !record.at(k).is_null() && text.empty()) text = record.at(k).get<std::string>();
    } else if (record.contains(key)) {
      const Json& v = record.at(key);
      const bool value = key != "name" && key != "intersecting" && key.find("_dir") == std::string::npos;
      text = value ? cell(v, format) : v.is_null() ? "" : v.is_boolean() ? (v.get<bool>() ? "true" : "false")
                                                                          : v.get<std::string>();
    }
    if (format == RecordFormat::Csv) {
      const bool quote = key == "name" || key == "error";
      out += (first ? "" : ",") + (quote && !text.empty() ? csv_quoted(text) : text);
    } else {
      if (key == "name") text = printable(text);
      out += width ? padded(text, width) : text;
    }
    first = false;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace pdd::io
