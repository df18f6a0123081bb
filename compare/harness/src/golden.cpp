#include "pdd/compare/golden.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "pdd/compare/engines.h"
#include "pdd/io/golden_files.h"
#include "pdd/io/output.h"
#include "pdd/io/result_json.h"

namespace pdd::compare {
using io::FixtureFile;
using io::Json;
using io::golden_fixture_files;
using io::golden_path;
using io::read_fixture_file;
using io::read_result_lines;
using io::write_file;
namespace fs = std::filesystem;

ExactLines exact_json_lines(const std::string& fixture_path, QpFormulation f, bool progress) {
  const FixtureFile file = read_fixture_file(fixture_path);
  if (file.error) throw std::runtime_error(*file.error);
  ExactLines out;
  for (const auto& r : run_reference(file.entries, {f}, progress)) {
    out.text += exact_record(r).dump() + "\n";
    if (r.error) out.rejected.push_back("pair '" + printable(r.name) + "': " + *r.error);
  }
  return out;
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first line that differs, both versions, for the report.
std::string first_difference(const std::string& want, const std::string& got) {
  std::istringstream a(want), b(got);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ha = bool(std::getline(a, la)), hb = bool(std::getline(b, lb));
    if (!ha && !hb) return "identical";
    if (la != lb || ha != hb)
      return "line " + std::to_string(line) + "\n  golden: " + (ha ? la : "<none>") +
             "\n  now:    " + (hb ? lb : "<none>");
  }
}

}  // namespace

std::vector<GoldenMismatch> check_golden(const std::string& fixtures_dir, QpFormulation f, bool progress) {
  std::vector<GoldenMismatch> out;
  for (const auto& rel : golden_fixture_files(fixtures_dir)) {
    const std::string gpath = golden_path(fixtures_dir, rel);
    if (!fs::exists(gpath)) {
      out.push_back({rel, "no golden file " + gpath + " (run pdd golden --update)"});
      continue;
    }
    if (progress) std::cerr << "pdd golden: checking " << rel << "\n";
    const std::string want = read_text(gpath);
    const ExactLines got = exact_json_lines((fs::path(fixtures_dir) / rel).string(), f, progress);
    for (const auto& why : got.rejected)
      out.push_back({rel, why + " (rejected: a golden file holds computed records only)"});
    if (want != got.text) out.push_back({rel, first_difference(want, got.text)});
  }
  return out;
}

std::vector<reference::ExactResult> read_golden(const std::string& path) {
  return read_result_lines<reference::Rational>(
      path, [](const Json& j) { return reference::Rational(j.get<std::string>()); });
}

std::vector<std::string> update_golden(const std::string& fixtures_dir, QpFormulation f, bool progress) {
  std::vector<std::pair<std::string, std::string>> files;  // (relative path, text)
  std::string rejected;
  for (const auto& rel : golden_fixture_files(fixtures_dir)) {
    if (progress) std::cerr << "pdd golden: computing " << rel << "\n";
    ExactLines lines = exact_json_lines((fs::path(fixtures_dir) / rel).string(), f, progress);
    for (const auto& why : lines.rejected) rejected += "\n  " + rel + ": " + why;
    files.emplace_back(rel, std::move(lines.text));
  }
  if (!rejected.empty())
    throw GoldenRejection("nothing written: a golden file holds computed records only, and the exact "
                             "engine rejects" + rejected);
  std::vector<std::string> written;
  for (const auto& [rel, text] : files) {
    const std::string gpath = golden_path(fixtures_dir, rel);
    fs::create_directories(fs::path(gpath).parent_path());
    if (auto why = write_file(gpath, text)) throw std::runtime_error(*why);
    written.push_back(rel);
  }
  return written;
}

}  // namespace pdd::compare
