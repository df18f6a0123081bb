// fixtures.h — test access to the shipped fixture files (PDD_FIXTURES_DIR from CMake), through
// io/ (pdd_io) only.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/compare/fixture_io.h"
#include "pdd/compare/golden_files.h"

namespace pdd::test {

inline std::string fixture_path(const std::string& file) {
  return std::string(PDD_FIXTURES_DIR) + "/" + file;
}

// Every well-formed pair of a fixture file; throws if the file or an entry is malformed.
inline std::vector<TetPair> load_pairs(const std::string& file) {
  const auto f = compare::read_fixture_file(fixture_path(file));
  if (f.error) throw std::runtime_error(*f.error);
  std::vector<TetPair> out;
  for (const auto& e : f.entries) {
    if (e.error) throw std::runtime_error(e.pair.name + ": " + *e.error);
    out.push_back(e.pair);
  }
  return out;
}

inline TetPair load_pair(const std::string& file, const std::string& name) {
  for (auto& p : load_pairs(file))
    if (p.name == name) return p;
  throw std::runtime_error("no pair '" + name + "' in " + file);
}

// The fixture files every engine-wide property is checked on: all shipped fixtures with golden
// files (smoke, degenerate, and every generated family).
inline std::vector<std::string> property_fixture_files() {
  return compare::golden_fixture_files(PDD_FIXTURES_DIR);
}

}  // namespace pdd::test
