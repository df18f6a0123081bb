#include "pdd/io/fixture_io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <tuple>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <istream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_set>

namespace pdd::io {
namespace {

using nlohmann::json;

// ------------------------------------------------------------------------------------------
// The bytes the JSON lexer sees.
//
// nlohmann::json refuses a document holding a number beyond the double range (1e400), but
// definitions §1 wants only that pair rejected, as non-finite. So the bytes pass through this
// filter on their way to the lexer: outside strings, each maximal run of number characters
// [-+.0-9eE] is checked against the JSON number grammar; a valid number that overflows a
// double is handed to the lexer as a zero of the same length ("1e400" -> "0e000") and its
// ordinal among the document's numbers is queued, so that the SAX handler, counting the
// numbers it is given, turns exactly that one into +-infinity. A run that is not a valid
// number is passed on unchanged: the lexer rejects it (a valid number is never followed
// directly by one of those characters). Lengths are kept, so the lexer's byte positions are
// the file's. NUL bytes are handed on as 0x01 (the lexer would take NUL for the end of the
// input and ignore the rest) and remembered, so the error names them.
class FilteredInput {
 public:
  explicit FilteredInput(std::istream& in) : in_(in), block_(1 << 16) {}

  int peek() {
    if (out_pos_ == out_.size()) fill();
    return out_pos_ < out_.size() ? static_cast<unsigned char>(out_[out_pos_]) : EOF;
  }
  void advance() {
    if (out_pos_ < out_.size()) ++out_pos_;
  }

  // Facts for the SAX handler and its messages.
  std::size_t numbers = 0;                              // valid number tokens read so far
  std::deque<std::pair<std::size_t, bool>> overflows;   // (ordinal, negative), in order
  std::optional<std::size_t> first_nul;                 // byte offset of the first NUL
  std::optional<std::pair<std::size_t, std::string>> bad_number;  // first malformed number
  std::size_t last_string_start = 0;                    // offset of the last '"' opening a string
  std::size_t last_open = 0;                            // offset of the last '{' or '['
  std::size_t last_scalar = 0;                          // offset of the last scalar token
  // Integer literals that are not exactly a double (definitions §1 reads coordinates as doubles; an
  // integer such as 9007199254740993 would silently become another integer): (ordinal among
  // the numbers, byte offset, text), in order. The entry holding one is rejected, naming it.
  std::deque<std::tuple<std::size_t, std::size_t, std::string>> inexact;
  bool saw_content = false;                             // a byte other than white space
  std::optional<std::string> read_error;

 private:
  int raw_peek() {
    if (pos_ == len_) {
      if (eof_) return EOF;
      in_.read(block_.data(), static_cast<std::streamsize>(block_.size()));
      len_ = static_cast<std::size_t>(in_.gcount());
      pos_ = 0;
      if (in_.bad() && !read_error) read_error = std::strerror(errno ? errno : EIO);
      if (len_ == 0) {
        eof_ = true;
        return EOF;
      }
    }
    return static_cast<unsigned char>(block_[pos_]);
  }
  int raw_get() {
    const int c = raw_peek();
    if (c != EOF) ++pos_, ++offset_;
    return c;
  }
  static bool number_char(int c) {
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
  }
  // The JSON number grammar: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
  static bool valid_number(const std::string& s) {
    std::size_t i = 0, n = s.size();
    auto digits = [&] {
      const std::size_t from = i;
      while (i < n && s[i] >= '0' && s[i] <= '9') ++i;
      return i > from;
    };
    if (i < n && s[i] == '-') ++i;
    if (i < n && s[i] == '0') ++i;
    else if (!(i < n && s[i] >= '1' && s[i] <= '9') || !digits()) return false;
    if (i < n && s[i] == '.') {
      ++i;
      if (!digits()) return false;
    }
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
      ++i;
      if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
      if (!digits()) return false;
    }
    return i == n;
  }

  // Whether the integer literal `text` (JSON grammar, no fraction or exponent) denotes exactly
  // the double `value` it was read as: glibc prints a double's exact decimal expansion.
  static bool integer_is_exact(const std::string& text, double value) {
    if (!std::isfinite(value)) return false;  // beyond the double range (10^400): named too
    char buf[400];
    std::snprintf(buf, sizeof buf, "%.0f", std::fabs(value));
    const std::string digits = text[0] == '-' ? text.substr(1) : text;
    return digits == buf;
  }

  void fill() {
    out_.clear();
    out_pos_ = 0;
    const std::size_t at = offset_;
    int c = raw_get();
    if (c == EOF) return;
    if (c == 0) {
      if (!first_nul) first_nul = at;
      c = 1;
    }
    if (in_string_) {
      if (escaped_) escaped_ = false;
      else if (c == '\\') escaped_ = true;
      else if (c == '"') in_string_ = false;
      out_.push_back(static_cast<char>(c));
      return;
    }
    if (c == '"') {
      in_string_ = true;
      last_string_start = last_scalar = at;
      saw_content = true;
      out_.push_back('"');
      return;
    }
    if (c != ' ' && c != '\t' && c != '\r' && c != '\n') saw_content = true;
    if (c == '{' || c == '[') last_open = at;
    const bool letter = c >= 'a' && c <= 'z';
    if (letter && !after_letter_) last_scalar = at;  // true, false, null
    after_letter_ = letter;
    if (c != '-' && !(c >= '0' && c <= '9')) {
      out_.push_back(static_cast<char>(c));
      return;
    }
    last_scalar = at;
    out_.push_back(static_cast<char>(c));
    while (number_char(raw_peek())) out_.push_back(static_cast<char>(raw_get()));
    if (!valid_number(out_)) {
      if (!bad_number) bad_number.emplace(at, out_.substr(0, 40));
      return;
    }
    ++numbers;
    const double value = std::strtod(out_.c_str(), nullptr);
    if (out_.find_first_of(".eE") == std::string::npos && !integer_is_exact(out_, value))
      inexact.emplace_back(numbers, at, out_.substr(0, 60));
    if (std::isfinite(value)) return;
    const bool negative = out_[0] == '-';
    overflows.emplace_back(numbers, negative);
    const std::size_t len = out_.size();  // >= 5: the shortest overflow is 2e308
    out_ = negative ? "-0e" : "0e";
    out_.append(len - out_.size(), '0');
  }

  std::istream& in_;
  std::vector<char> block_;
  std::size_t pos_ = 0, len_ = 0, offset_ = 0;
  bool eof_ = false, in_string_ = false, escaped_ = false, after_letter_ = false;
  std::string out_;
  std::size_t out_pos_ = 0;
};

// The lexer reads FilteredInput through this input iterator (value_type char).
struct FilteredIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = char;

  FilteredInput* in = nullptr;  // nullptr: the end
  char operator*() const { return static_cast<char>(in->peek()); }
  FilteredIterator& operator++() {
    in->advance();
    return *this;
  }
  bool at_end() const { return in == nullptr || in->peek() == EOF; }
  bool operator==(const FilteredIterator& o) const { return at_end() == o.at_end(); }
  bool operator!=(const FilteredIterator& o) const { return !(*this == o); }
};

// ------------------------------------------------------------------------------------------
// One entry, from the small tree the handler builds for it.

std::optional<double> coordinate(const json& v) {
  if (v.is_number()) return v.get<double>();
  return std::nullopt;
}

const char* type_name(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "a number";
  }
}

// One tetrahedron: exactly 4 vertices of exactly 3 numbers.
std::optional<std::string> read_tet(const json& entry, const char* key, TetVertices& out) {
  if (!entry.contains(key)) return std::string("missing field '") + key + "'";
  const json& t = entry.at(key);
  if (!t.is_array() || t.size() != 4)
    return std::string("field '") + key + "' must be an array of 4 vertices";
  for (int i = 0; i < 4; ++i) {
    const json& v = t[i];
    if (!v.is_array() || v.size() != 3)
      return std::string("field '") + key + "' vertex " + std::to_string(i) +
             " must be an array of 3 numbers";
    for (int k = 0; k < 3; ++k) {
      const std::optional<double> x = coordinate(v[k]);
      if (!x)
        return std::string("field '") + key + "' vertex " + std::to_string(i) + " coordinate " +
               "xyz"[k] + " is not a number";
      out[i][k] = *x;
    }
  }
  return std::nullopt;
}

FixtureEntry read_entry(const json& entry, std::size_t index, std::size_t start_byte) {
  FixtureEntry e;
  e.pair.name = "#" + std::to_string(index + 1) + " (byte " + std::to_string(start_byte) + ")";
  if (!entry.is_object()) {
    e.error = std::string("entry is not a JSON object (it is ") + type_name(entry) + ")";
    return e;
  }
  const auto name = entry.find("name");
  if (name == entry.end() || (name->is_string() && name->get<std::string>().empty())) {
    e.error = "missing or empty string field 'name'";
    return e;
  }
  if (!name->is_string()) {
    e.error = std::string("field 'name' must be a string, not ") + type_name(*name);
    return e;
  }
  e.pair.name = name->get<std::string>();
  if (entry.contains("tags")) {
    const json& tags = entry["tags"];
    bool ok = tags.is_array();
    for (std::size_t k = 0; ok && k < tags.size(); ++k) ok = tags[k].is_string();
    if (!ok) {
      e.error = "field 'tags' must be an array of strings";
      return e;
    }
    for (const json& t : tags) e.pair.tags.push_back(t.get<std::string>());
  }
  if (auto why = read_tet(entry, "A", e.pair.A)) e.error = why;
  else if (auto why_b = read_tet(entry, "B", e.pair.B)) e.error = why_b;
  return e;
}

// ------------------------------------------------------------------------------------------
// The SAX handler: tracks where in the document it is, rejects duplicate keys anywhere,
// builds a small tree for one entry of "pairs" at a time and hands finished entries over.

class FixtureHandler {
 public:
  FixtureHandler(FilteredInput& in, bool count_only, std::size_t chunk_size,
                 const FixtureSink* sink)
      : in_(in), count_only_(count_only), chunk_size_(chunk_size ? chunk_size : 1), sink_(sink) {}

  std::optional<std::string> error;
  bool stopped = false;  // the sink asked to stop
  std::size_t entries = 0;

  // The document had no usable "pairs" array.
  bool shapeless() const { return !top_object_ || !pairs_array_; }
  bool flush() {
    if (chunk_.empty() || !sink_) return true;
    const bool go_on = (*sink_)(chunk_, first_index_);
    first_index_ += chunk_.size();
    chunk_.clear();
    if (!go_on) stopped = true;
    return go_on;
  }

  // SAX interface (nlohmann::json_sax).
  bool null() { return scalar(json(nullptr)); }
  bool boolean(bool v) { return scalar(json(v)); }
  bool number_integer(json::number_integer_t v) { return number(static_cast<double>(v), json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return number(static_cast<double>(v), json(v)); }
  bool number_float(json::number_float_t v, const std::string&) { return number(v, json(v)); }
  bool string(std::string& v) { return scalar(json(std::move(v))); }
  bool binary(json::binary_t&) { return scalar(json(nullptr)); }  // not produced by JSON text
  bool start_object(std::size_t) { return open(true); }
  bool start_array(std::size_t) { return open(false); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(std::string& k) {
    if (!keys_.back().insert(k).second) {
      error = "duplicate key \"" + k.substr(0, 60) + "\" at byte " +
              std::to_string(in_.last_string_start) + " (each key may appear once per object)";
      return false;
    }
    if (containers_.size() == 1) top_key_ = k;
    if (building_) key_ = std::move(k);
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) {
    if (in_.read_error) error = "read error: " + *in_.read_error;
    else if (in_.first_nul) error = "NUL byte at byte " + std::to_string(*in_.first_nul) + " (not a text file)";
    else if (!in_.saw_content) error = "file is empty";
    else if (in_.bad_number)
      error = "malformed JSON at byte " + std::to_string(in_.bad_number->first) + ": '" +
              in_.bad_number->second + "' is not a valid number";
    else {
      std::string what = ex.what();
      if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
        what = what.substr(what.find("] ") + 2);
      error = "malformed JSON at byte " + std::to_string(position) + ": " + what;
    }
    return false;
  }

 private:
  // Called before any value (scalar or container) at the current depth.
  void begin_value(bool container, bool object) {
    const std::size_t depth = containers_.size();
    if (depth == 0) {
      top_object_ = object;
    } else if (depth == 1 && top_object_ && top_key_ == "pairs") {
      pairs_array_ = container && !object;
      pairs_open_ = pairs_array_;
    } else if (depth == 2 && pairs_open_ && !building_) {
      index_ = entries++;
      // the entry starts at the bracket, or the scalar token, the lexer has just read
      start_byte_ = container ? in_.last_open : in_.last_scalar;
      inexact_.reset();
      building_ = !count_only_;
    }
  }
  bool number(double value, json v) {
    ++numbers_;
    while (!in_.inexact.empty() && std::get<0>(in_.inexact.front()) < numbers_) in_.inexact.pop_front();
    const bool inexact = !in_.inexact.empty() && std::get<0>(in_.inexact.front()) == numbers_;
    if (inexact && building_ && !inexact_)
      inexact_ = "the integer " + std::get<2>(in_.inexact.front()) +
                 (std::get<2>(in_.inexact.front()).size() >= 60 ? "..." : "") + " at byte " +
                 std::to_string(std::get<1>(in_.inexact.front())) +
                 (in_.overflows.empty() || in_.overflows.front().first != numbers_
                      ? " is not exactly a double (coordinates are doubles; write it as one, e.g. " +
                            nearest(value) + ")"
                      : " is beyond the largest double (not finite)");
    if (inexact) in_.inexact.pop_front();
    if (!in_.overflows.empty() && in_.overflows.front().first == numbers_) {
      value = in_.overflows.front().second ? -std::numeric_limits<double>::infinity()
                                           : std::numeric_limits<double>::infinity();
      in_.overflows.pop_front();
      v = json(value);
    }
    return scalar(std::move(v));
  }
  bool scalar(json v) {
    begin_value(false, false);
    if (!building_) return true;
    put(std::move(v));
    if (build_.empty()) return finish_entry();  // the entry itself was a scalar
    return true;
  }
  bool open(bool object) {
    begin_value(true, object);
    containers_.push_back(object);
    if (object) keys_.emplace_back();
    if (building_) build_.push_back(put(object ? json::object() : json::array()));
    return true;
  }
  bool close() {
    if (containers_.back()) keys_.pop_back();
    containers_.pop_back();
    if (containers_.size() == 1 && pairs_open_) pairs_open_ = false;
    if (building_) {
      build_.pop_back();
      if (build_.empty()) return finish_entry();
    }
    return true;
  }
  json* put(json v) {
    if (build_.empty()) {
      entry_ = std::move(v);
      return &entry_;
    }
    json& parent = *build_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(v));
      return &parent.back();
    }
    json& slot = parent[key_];
    slot = std::move(v);
    return &slot;
  }
  static std::string nearest(double v) {
    char buf[400];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
  }
  bool finish_entry() {
    building_ = false;
    chunk_.push_back(read_entry(entry_, index_, start_byte_));
    if (inexact_ && !chunk_.back().error) chunk_.back().error = inexact_;
    entry_ = nullptr;
    return chunk_.size() < chunk_size_ || flush();
  }

  FilteredInput& in_;
  bool count_only_;
  std::size_t chunk_size_;
  const FixtureSink* sink_;
  std::vector<bool> containers_;  // open containers, true = object
  std::vector<std::unordered_set<std::string>> keys_;  // keys seen, per open object
  std::string top_key_;
  bool top_object_ = false, pairs_array_ = false, pairs_open_ = false;
  bool building_ = false;
  std::size_t index_ = 0, numbers_ = 0, start_byte_ = 0;
  std::optional<std::string> inexact_;  // the entry's first inexact integer, worded
  json entry_;
  std::vector<json*> build_;
  std::string key_;
  std::vector<FixtureEntry> chunk_;
  std::size_t first_index_ = 0;
};

struct ParseOutcome {
  std::size_t entries = 0;
  std::optional<std::string> error;
  bool stopped = false;
};

ParseOutcome parse_stream(std::istream& in, bool count_only, std::size_t chunk_size,
                          const FixtureSink* sink) {
  FilteredInput input(in);
  FixtureHandler handler(input, count_only, chunk_size, sink);
  FilteredIterator first{&input}, last{nullptr};
  bool ok = false;
  try {
    ok = json::sax_parse(first, last, &handler);
  } catch (const std::exception& e) {  // nothing in the handler throws; be safe anyway
    handler.error = std::string("malformed JSON: ") + e.what();
  }
  ParseOutcome out;
  out.entries = handler.entries;
  if (handler.stopped) {
    out.stopped = true;
    return out;
  }
  if (input.read_error) out.error = "read error: " + *input.read_error;
  else if (handler.error) out.error = handler.error;
  else if (!ok) out.error = "malformed JSON";
  else if (handler.shapeless()) out.error = "expected an object with an array field 'pairs'";
  else if (!handler.flush()) out.stopped = true;
  return out;
}

// Opens `path` for reading, or says honestly why not.
std::optional<std::string> open_input(const std::string& path, std::ifstream& in) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return "cannot read '" + path + "': it is a directory, not a fixture file";
  errno = 0;
  in.open(path, std::ios::binary);
  if (!in) return "cannot open '" + path + "': " + std::strerror(errno ? errno : ENOENT);
  return std::nullopt;
}

}  // namespace

FixtureFile parse_fixture_text(const std::string& text) {
  std::istringstream in(text);
  FixtureFile f;
  const FixtureSink keep = [&f](std::vector<FixtureEntry>& chunk, std::size_t) {
    for (auto& e : chunk) f.entries.push_back(std::move(e));
    return true;
  };
  const ParseOutcome r =
      parse_stream(in, false, std::numeric_limits<std::size_t>::max(), &keep);
  if (r.error) {
    f.entries.clear();
    f.error = r.error;
  }
  return f;
}

FixtureFile read_fixture_file(const std::string& path) {
  FixtureFile f;
  std::ifstream file;
  if (path != "-") {
    if (auto why = open_input(path, file)) {
      f.error = why;
      return f;
    }
  }
  std::istream& in = path == "-" ? std::cin : file;
  const FixtureSink keep = [&f](std::vector<FixtureEntry>& chunk, std::size_t) {
    for (auto& e : chunk) f.entries.push_back(std::move(e));
    return true;
  };
  const ParseOutcome r = parse_stream(in, false, std::numeric_limits<std::size_t>::max(), &keep);
  if (r.error) {
    f.entries.clear();
    f.error = path + ": " + *r.error;
  }
  return f;
}

FixtureCheck check_fixture_file(const std::string& path) {
  FixtureCheck c;
  std::ifstream in;
  if (auto why = open_input(path, in)) {
    c.error = why;
    return c;
  }
  const ParseOutcome r = parse_stream(in, true, 1, nullptr);
  c.entries = r.entries;
  if (r.error) c.error = path + ": " + *r.error;
  return c;
}

std::optional<std::string> stream_fixture_file(const std::string& path, std::size_t chunk_size,
                                               const FixtureSink& sink) {
  std::ifstream in;
  if (auto why = open_input(path, in)) return why;
  const ParseOutcome r = parse_stream(in, false, chunk_size, &sink);
  if (r.error) return path + ": " + *r.error;
  return std::nullopt;
}

std::string fixture_json_entry(const TetPair& p) {
  nlohmann::ordered_json e;
  e["name"] = p.name;
  e["tags"] = p.tags;
  e["A"] = p.A;
  e["B"] = p.B;
  return e.dump();
}

std::string fixture_json(const std::vector<TetPair>& pairs) {
  // One pair per line keeps diffs of generated fixture files reviewable.
  std::string out = kFixtureJsonHead;
  for (std::size_t k = 0; k < pairs.size(); ++k)
    out += "  " + fixture_json_entry(pairs[k]) + (k + 1 < pairs.size() ? ",\n" : "\n");
  return out + kFixtureJsonTail;
}

}  // namespace pdd::io
