// record_line.cpp — see record_line.h: emit_record's keys written as text.
#include "pdd/io/record_line.h"

#include <cmath>
#include <cstring>

namespace pdd::io {
namespace {

void append_number(std::string& s, double x) {
  if (!std::isfinite(x)) {  // (as nlohmann's serializer: a non-finite number is written null)
    s += "null";
    return;
  }
  char buffer[64];  // (the serializer's number buffer)
  const char* end = nlohmann::detail::to_chars(buffer, buffer + sizeof buffer, x);
  s.append(buffer, static_cast<std::size_t>(end - buffer));
}
void append_number(std::string& s, const Rational& q) {
  s += '"';
  s += q.get_str();  // digits, '-' and '/': nothing to escape
  s += '"';
}
void append_text(std::string& s, const std::string& t) {
  for (const char c : t)
    if (c < 0x20 || c > 0x7e || c == '"' || c == '\\') {
      s += Json(t).dump();  // nlohmann's escaping (and its error on invalid UTF-8)
      return;
    }
  s += '"';
  s += t;
  s += '"';
}

template <class R>
class LineWriter {
 public:
  LineWriter(std::string& s, unsigned variants, bool name) : s_(s), variants_(variants), name_(name) {}
  bool key(const char* k) {
    if ((!name_ && std::strcmp(k, "name") == 0) || !asked_key(k, variants_)) return false;
    s_ += first_ ? "\"" : ",\"";
    first_ = false;
    s_ += k;  // (the keys are plain ASCII: nothing to escape)
    s_ += "\":";
    return true;
  }
  void number(const R& x) { append_number(s_, x); }
  void null() { s_ += "null"; }
  void boolean(bool b) { s_ += b ? "true" : "false"; }
  void text(const std::string& t) { append_text(s_, t); }
  void row(const std::array<R, 3>& v) {
    s_ += '[';
    for (int k = 0; k < 3; ++k) {
      if (k) s_ += ',';
      number(v[k]);
    }
    s_ += ']';
  }
  template <class Rows>
  void rows(const Rows& a) {
    s_ += '[';
    bool first = true;
    for (const auto& v : a) {
      if (!first) s_ += ',';
      first = false;
      row(v);
    }
    s_ += ']';
  }
  void continues() { first_ = false; }

 private:
  std::string& s_;
  unsigned variants_;
  bool name_;
  bool first_ = true;
};

template <class R>
std::string line(const PairResult<R>& r, unsigned variants) {
  std::string s = "{";
  s.reserve(1024);
  LineWriter<R> w(s, variants, true);
  emit_record(r, w);
  s += '}';
  return s;
}
template <class R>
std::string contact(std::size_t a, std::size_t b, const PairResult<R>& r, unsigned variants) {
  std::string s = "{\"a\":" + std::to_string(a) + ",\"b\":" + std::to_string(b);
  s.reserve(1024);
  LineWriter<R> w(s, variants, false);
  w.continues();
  emit_record(r, w);
  s += '}';
  return s;
}

}  // namespace

std::string record_line(const PairResult<double>& r, unsigned variants) { return line(r, variants); }
std::string record_line(const PairResult<Rational>& r, unsigned variants) { return line(r, variants); }
std::string contact_line(std::size_t a, std::size_t b, const PairResult<double>& r, unsigned variants) {
  return contact(a, b, r, variants);
}
std::string contact_line(std::size_t a, std::size_t b, const PairResult<Rational>& r, unsigned variants) {
  return contact(a, b, r, variants);
}

}  // namespace pdd::io
