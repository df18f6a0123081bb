#include "pdd/compare/golden.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pdd/compare/engines.h"
#include "pdd/compare/golden_files.h"
#include "pdd/compare/output.h"
#include "pdd/compare/result_json.h"

namespace pdd::compare {
namespace fs = std::filesystem;

std::string exact_json_lines(const std::string& fixture_path, QpFormulation f) {
  const FixtureFile file = read_fixture_file(fixture_path);
  if (file.error) throw std::runtime_error(*file.error);
  std::string out;
  for (const auto& r : run_reference(file.entries, {f}, false)) out += exact_record(r).dump() + "\n";
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

std::vector<GoldenMismatch> check_golden(const std::string& fixtures_dir, QpFormulation f) {
  std::vector<GoldenMismatch> out;
  for (const auto& rel : golden_fixture_files(fixtures_dir)) {
    const std::string gpath = golden_path(fixtures_dir, rel);
    if (!fs::exists(gpath)) {
      out.push_back({rel, "no golden file " + gpath + " (run pdd golden --update)"});
      continue;
    }
    const std::string want = read_text(gpath);
    const std::string got = exact_json_lines((fs::path(fixtures_dir) / rel).string(), f);
    if (want != got) out.push_back({rel, first_difference(want, got)});
  }
  return out;
}

std::vector<reference::ExactResult> read_golden(const std::string& path) {
  return read_result_lines<reference::Rational>(
      path, [](const Json& j) { return reference::Rational(j.get<std::string>()); });
}

std::vector<std::string> update_golden(const std::string& fixtures_dir, QpFormulation f) {
  std::vector<std::string> written;
  for (const auto& rel : golden_fixture_files(fixtures_dir)) {
    const std::string gpath = golden_path(fixtures_dir, rel);
    fs::create_directories(fs::path(gpath).parent_path());
    if (auto why = write_file(gpath, exact_json_lines((fs::path(fixtures_dir) / rel).string(), f)))
      throw std::runtime_error(*why);
    written.push_back(rel);
  }
  return written;
}

}  // namespace pdd::compare
