// fixture_io.h — reading fixture files (definitions §1) without losing a single pair.
//
// Input : a path to a JSON file {"pairs": [{"name", "tags"?, "A", "B"}, ...]}.
// Output: every entry of "pairs" in order, each either a TetPair or the reason it could not
//         be read (missing or mistyped field, wrong shape); or a file-level error when the
//         file cannot be read, is empty, is not JSON, or has no "pairs" array. Coordinates are
//         parsed as doubles exactly as written (a decimal or exponent literal: the nearest
//         double); a syntactically valid number too large for a double (1e400) becomes
//         +-infinity and is rejected by the engines' validation, not here; an integer literal
//         that is not exactly a double (9007199254740993) rejects its entry, naming the integer
//         and its byte (the Python module rejects such an int too). A file-level error names
//         the byte where it was found. The path "-" is standard input.
//
// The file is read with nlohmann::json's SAX interface, so no document tree is ever built:
// only one entry at a time is held, and stream_fixture_file hands entries over in chunks.
// What makes a whole file unreadable: it cannot be opened or read, is a directory, is
// empty, is not JSON (malformed numbers such as 1.e400 or -01, trailing garbage), holds a
// NUL byte, repeats a key in any object, or has no "pairs" array. What rejects only one
// entry: it is not an object; 'name' is missing, empty or not a string; 'tags' is not an
// array of strings; 'A' or 'B' is missing or not 4 vertices of 3 numbers.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pdd/tet_pair.h"

namespace pdd::io {

struct FixtureEntry {
  TetPair pair;  // name is "#<k> (byte <b>)" when the entry has no usable name: its 1-based
                 // position in "pairs" and the byte where it starts
  std::optional<std::string> error;  // set when the entry is malformed
};

struct FixtureFile {
  std::vector<FixtureEntry> entries;
  std::optional<std::string> error;  // set when nothing could be read
};

FixtureFile read_fixture_file(const std::string& path);
FixtureFile parse_fixture_text(const std::string& text);

// Reads the whole file without keeping any pair: the number of entries, or the file-level
// error. Lets a caller refuse a bad file before computing anything, and size its progress.
struct FixtureCheck {
  std::size_t entries = 0;
  std::optional<std::string> error;
};
FixtureCheck check_fixture_file(const std::string& path);

// Reads `path` once, handing its entries to `sink` in input order in chunks of at most
// `chunk_size` (the last may be shorter; `first_index` is the chunk's first entry's index).
// The sink returns false to stop reading. Returns the file-level error, if any; chunks read
// before an error has been found have already been handed over (run check_fixture_file
// first when that matters). Memory use does not grow with the file.
using FixtureSink = std::function<bool(std::vector<FixtureEntry>& chunk, std::size_t first_index)>;
std::optional<std::string> stream_fixture_file(const std::string& path, std::size_t chunk_size,
                                               const FixtureSink& sink);

// Writes pairs back in the same format (round-trip exact: doubles in shortest exact form): the
// head, one line per pair ("  " + fixture_json_entry, a comma after all but the last), the tail.
std::string fixture_json(const std::vector<TetPair>& pairs);
std::string fixture_json_entry(const TetPair& pair);
inline constexpr const char* kFixtureJsonHead = "{\"pairs\": [\n";
inline constexpr const char* kFixtureJsonTail = "]}\n";

}  // namespace pdd::io
