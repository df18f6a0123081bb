// golden.h — golden files: the exact engine's SPEC §6 output for every shipped fixture file.
//
// fixtures/X.json has its golden file fixtures/golden/X.jsonl (same relative path; finding and
// reading them: io/'s golden_files.h). Checking re-runs the exact engine and compares the
// records digit for digit; updating rewrites them, so that any change in an exact value shows
// up as a reviewable diff.
#pragma once

#include <string>
#include <vector>

#include "pdd/compare/golden_files.h"
#include "pdd/reference/direction_qp.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {

// The exact engine's JSON Lines for one fixture file (input order).
std::string exact_json_lines(const std::string& fixture_path, QpFormulation f);

struct GoldenMismatch {
  std::string file;
  std::string detail;  // first differing record, or a missing file
};

// Compares every golden file with a fresh exact run; empty when all match.
std::vector<GoldenMismatch> check_golden(const std::string& fixtures_dir, QpFormulation f);

// Reads a golden JSON Lines file back into exact results (numbers parsed as exact rationals,
// labels parsed); throws std::runtime_error on a malformed record.
std::vector<reference::ExactResult> read_golden(const std::string& path);

// Rewrites every golden file; returns the relative paths written.
std::vector<std::string> update_golden(const std::string& fixtures_dir, QpFormulation f);

}  // namespace pdd::compare
