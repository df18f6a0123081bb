#include "pdd/compare/fixture_io.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

namespace pdd::compare {
namespace {

using nlohmann::json;

// JSON numbers beyond the double range (1e999) make nlohmann reject the whole document. SPEC
// §1 wants such a pair rejected alone, as non-finite, so before parsing every number token
// outside strings that overflows is rewritten as the string kOverflowMarker + token, which
// read_tet turns back into +-infinity for the engines' validation to reject.
const std::string kOverflowMarker = "pdd:overflow:";

std::string mark_overflowing_numbers(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) out += text[++i];
      else if (c == '"') in_string = false;
      ++i;
    } else if (c == '"') {
      in_string = true;
      out += c, ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const std::size_t end = text.find_first_not_of("+-0123456789.eE", i);
      const std::string token = text.substr(i, end == std::string::npos ? end : end - i);
      const double v = std::strtod(token.c_str(), nullptr);
      out += std::isfinite(v) ? token : "\"" + kOverflowMarker + token + "\"";
      i += token.size();
    } else {
      out += c, ++i;
    }
  }
  return out;
}

// A coordinate: a JSON number, or an overflowing number marked above (-> +-infinity).
std::optional<double> coordinate(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string() && v.get<std::string>().rfind(kOverflowMarker, 0) == 0)
    return v.get<std::string>()[kOverflowMarker.size()] == '-'
               ? -std::numeric_limits<double>::infinity()
               : std::numeric_limits<double>::infinity();
  return std::nullopt;
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

FixtureEntry read_entry(const json& entry, std::size_t index) {
  FixtureEntry e;
  e.pair.name = "#" + std::to_string(index);
  if (!entry.is_object()) {
    e.error = "entry is not a JSON object";
    return e;
  }
  if (!entry.contains("name") || !entry["name"].is_string() || entry["name"].get<std::string>().empty()) {
    e.error = "missing or empty string field 'name'";
    return e;
  }
  e.pair.name = entry["name"].get<std::string>();
  if (entry.contains("tags")) {
    if (!entry["tags"].is_array()) {
      e.error = "field 'tags' must be an array of strings";
      return e;
    }
    for (const json& t : entry["tags"]) {
      if (!t.is_string()) {
        e.error = "field 'tags' must be an array of strings";
        return e;
      }
      e.pair.tags.push_back(t.get<std::string>());
    }
  }
  if (auto why = read_tet(entry, "A", e.pair.A)) e.error = why;
  else if (auto why_b = read_tet(entry, "B", e.pair.B)) e.error = why_b;
  return e;
}

}  // namespace

FixtureFile parse_fixture_text(const std::string& text) {
  FixtureFile f;
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    f.error = "file is empty";
    return f;
  }
  json doc;
  try {
    doc = json::parse(mark_overflowing_numbers(text));
  } catch (const json::exception& e) {
    f.error = std::string("malformed JSON: ") + e.what();
    return f;
  }
  if (!doc.is_object() || !doc.contains("pairs") || !doc["pairs"].is_array()) {
    f.error = "expected an object with an array field 'pairs'";
    return f;
  }
  const json& pairs = doc["pairs"];
  for (std::size_t k = 0; k < pairs.size(); ++k) f.entries.push_back(read_entry(pairs[k], k));
  return f;
}

FixtureFile read_fixture_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    FixtureFile f;
    f.error = "cannot open '" + path + "'";
    return f;
  }
  std::ostringstream buf;
  buf << in.rdbuf();
  FixtureFile f = parse_fixture_text(buf.str());
  if (f.error) f.error = path + ": " + *f.error;
  return f;
}

std::string fixture_json(const std::vector<TetPair>& pairs) {
  // One pair per line keeps diffs of generated fixture files reviewable.
  std::string out = "{\"pairs\": [\n";
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const TetPair& p = pairs[k];
    nlohmann::ordered_json e;
    e["name"] = p.name;
    e["tags"] = p.tags;
    e["A"] = p.A;
    e["B"] = p.B;
    out += "  " + e.dump() + (k + 1 < pairs.size() ? ",\n" : "\n");
  }
  return out + "]}\n";
}

}  // namespace pdd::compare
