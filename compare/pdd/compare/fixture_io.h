// fixture_io.h — reading fixture files (SPEC §1) without losing a single pair.
//
// Input : a path to a JSON file {"pairs": [{"name", "tags"?, "A", "B"}, ...]}.
// Output: every entry of "pairs" in order, each either a TetPair or the reason it could not
//         be read (missing or mistyped field, wrong shape); or a file-level error when the
//         file cannot be read, is empty, is not JSON, or has no "pairs" array. Coordinates are
//         parsed as doubles exactly as written; a number too large for a double becomes
//         infinite and is rejected by the engines' validation (SPEC §1), not here.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pdd/tet_pair.h"

namespace pdd::compare {

struct FixtureEntry {
  TetPair pair;                      // name is "#<index>" when the entry has no usable name
  std::optional<std::string> error;  // set when the entry is malformed
};

struct FixtureFile {
  std::vector<FixtureEntry> entries;
  std::optional<std::string> error;  // set when nothing could be read
};

FixtureFile read_fixture_file(const std::string& path);
FixtureFile parse_fixture_text(const std::string& text);

// Writes pairs back in the same format (round-trip exact: doubles in shortest exact form).
std::string fixture_json(const std::vector<TetPair>& pairs);

}  // namespace pdd::compare
