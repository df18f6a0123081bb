// golden_files.h — where the golden files live and how to read them back.
//
// fixtures/X.json has its golden file fixtures/golden/X.jsonl (same relative path): the exact
// engine's definitions §6 JSON Lines for that file. Checking and rewriting them needs the exact
// engine and lives in harness/ (golden.h); finding and reading them needs neither engine.
#pragma once

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pdd/io/result_json.h"
#include "pdd/pair_result.h"

namespace pdd::io {

// Fixture files below `fixtures_dir` that have golden files: every *.json except those under
// bad/ and golden/, sorted, as paths relative to fixtures_dir.
std::vector<std::string> golden_fixture_files(const std::string& fixtures_dir);

// fixtures_dir/golden/<relative path with .jsonl>.
std::string golden_path(const std::string& fixtures_dir, const std::string& relative);

// Reads a JSON Lines file of definitions §6 records (a golden file) in file order, numbers read by
// `number` (golden numbers are exact "p/q" strings); throws std::runtime_error naming the file
// when it cannot be opened or a record is malformed.
template <class R>
std::vector<PairResult<R>> read_result_lines(const std::string& path, const NumberReader<R>& number) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<PairResult<R>> out;
  for (std::string line; std::getline(in, line);) {
    try {
      out.push_back(result_from_json<R>(Json::parse(line), number));
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
  }
  return out;
}

}  // namespace pdd::io
