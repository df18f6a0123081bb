// golden.h — golden files: the exact engine's SPEC §6 output for every shipped fixture file.
//
// fixtures/X.json has its golden file fixtures/golden/X.jsonl (same relative path). Checking
// re-runs the exact engine and compares the records digit for digit; updating rewrites them,
// so that any change in an exact value shows up as a reviewable diff.
#pragma once

#include <string>
#include <vector>

#include "pdd/reference/direction_qp.h"
#include "pdd/reference/solve_exact.h"

namespace pdd::compare {

// Fixture files below `fixtures_dir` that have golden files: every *.json except those under
// bad/ and golden/, sorted, as paths relative to fixtures_dir.
std::vector<std::string> golden_fixture_files(const std::string& fixtures_dir);

// fixtures_dir/golden/<relative path with .jsonl>.
std::string golden_path(const std::string& fixtures_dir, const std::string& relative);

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
