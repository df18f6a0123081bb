// golden.h — golden files: the exact engine's definitions §6 output for every shipped fixture file.
//
// fixtures/X.json has its golden file fixtures/golden/X.jsonl (same relative path; finding and
// reading them: io/'s golden_files.h). Checking re-runs the exact engine and compares the
// records digit for digit; updating rewrites them, so that any change in an exact value shows
// up as a reviewable diff.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/io/golden_files.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {

// A golden file holds computed records only: a pair the exact engine rejects (a flat or
// non-finite tetrahedron, a malformed entry) has no place in one, since a golden file that
// pins a rejection would pass a check while testing nothing the fixture claims.

// The exact engine's JSON Lines for one fixture file (input order), and the rejections found
// ("pair 'x': why"). `progress`: show progress on standard error.
struct ExactLines {
  std::string text;
  std::vector<std::string> rejected;
};
ExactLines exact_json_lines(const std::string& fixture_path, QpFormulation f, bool progress = false);

struct GoldenMismatch {
  std::string file;
  std::string detail;  // first differing record, a missing file, or a rejected pair
};

// Compares every golden file with a fresh exact run; empty when all match. `progress`: one line
// per file and a progress bar on standard error.
std::vector<GoldenMismatch> check_golden(const std::string& fixtures_dir, QpFormulation f,
                                         bool progress = false);

// Reads a golden JSON Lines file back into exact results (numbers parsed as exact rationals,
// labels parsed); throws std::runtime_error on a malformed record.
std::vector<reference::ExactResult> read_golden(const std::string& path);

// Thrown by update_golden when the exact engine rejects a pair: nothing was written.
struct GoldenRejection : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Rewrites every golden file; returns the relative paths written. Computes every file first:
// when a pair is rejected it writes nothing and throws GoldenRejection naming the pairs.
std::vector<std::string> update_golden(const std::string& fixtures_dir, QpFormulation f,
                                       bool progress = false);

}  // namespace pdd::compare
