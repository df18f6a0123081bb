// fixtures.h — test access to the shipped fixture files (PDD_FIXTURES_DIR from CMake), through
// io/ (pdd_io) only.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/io/fixture_io.h"
#include "pdd/io/golden_files.h"

namespace pdd::test {

inline std::string fixture_path(const std::string& file) {
  return std::string(PDD_FIXTURES_DIR) + "/" + file;
}

// Every well-formed pair of the fixture file at `path`; throws if the file or an entry is
// malformed.
inline std::vector<TetPair> load_pairs_at(const std::string& path) {
  const auto f = io::read_fixture_file(path);
  if (f.error) throw std::runtime_error(*f.error);
  std::vector<TetPair> out;
  for (const auto& e : f.entries) {
    if (e.error) throw std::runtime_error(e.pair.name + ": " + *e.error);
    out.push_back(e.pair);
  }
  return out;
}

// The same for a shipped fixture file (relative to fixtures/).
inline std::vector<TetPair> load_pairs(const std::string& file) { return load_pairs_at(fixture_path(file)); }

inline TetPair load_pair(const std::string& file, const std::string& name) {
  for (auto& p : load_pairs(file))
    if (p.name == name) return p;
  throw std::runtime_error("no pair '" + name + "' in " + file);
}

// The fixture files every engine-wide property is checked on: all shipped fixtures with golden
// files (smoke, degenerate, and every generated family).
inline std::vector<std::string> property_fixture_files() {
  return io::golden_fixture_files(PDD_FIXTURES_DIR);
}

}  // namespace pdd::test
